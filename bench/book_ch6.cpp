#include "book_ch6.h"

#include <memory>

#include "book_world.h"

namespace raycast::bench {

using book::hittable;
using book::hittable_list;
using book::ray_color;

struct book_ch6::world {
  hittable_list list;
};

book_ch6::book_ch6(const scene& s) : scene_(s), world_(std::make_unique<world>()) {
  for (const raycast::sphere& sp : s.spheres)
    world_->list.add(std::make_shared<book::sphere>(to_glm(sp.center), sp.radius));
}

book_ch6::~book_ch6() = default;

void book_ch6::render(const image_band& band) const {
  const camera& cam = scene_.cam;
  const int64_t W = cam.image_width, H = cam.image_height;
  const hittable& list = world_->list;
  for (int64_t row = band.row_begin; row < band.row_end; ++row) {
    const int64_t j = H - 1 - row;
    unsigned char* out = band.row(row);
    for (int64_t i = 0; i < W; ++i) {
      const double u = double(i) / double(W - 1);
      const double v = double(j) / double(H - 1);
      const ray r(cam.origin, cam.lower_left_corner + u * cam.horizontal + v * cam.vertical - cam.origin);
      const color c = ray_color(r, list);
      out[3 * i + 0] = static_cast<unsigned char>(static_cast<int>(255.999 * c.x));
      out[3 * i + 1] = static_cast<unsigned char>(static_cast<int>(255.999 * c.y));
      out[3 * i + 2] = static_cast<unsigned char>(static_cast<int>(255.999 * c.z));
    }
  }
}

}  // namespace raycast::bench
