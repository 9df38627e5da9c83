#include "book_ch6.h"

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>

namespace raycast::bench {
namespace {

// hittable.h
struct hit_record {
  point3 p;
  vec3 normal;
  double t;
  bool front_face;

  void set_face_normal(const ray& r, const vec3& outward_normal) {
    front_face = glm::dot(r.direction(), outward_normal) < 0;
    normal = front_face ? outward_normal : -outward_normal;
  }
};

class hittable {
 public:
  virtual ~hittable() = default;
  virtual bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const = 0;
};

// sphere.h
class book_sphere : public hittable {
 public:
  book_sphere(point3 cen, double r) : center(cen), radius(r) {}
  bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const override {
    const vec3 oc = r.origin() - center;
    const double a = glm::dot(r.direction(), r.direction());
    const double half_b = glm::dot(oc, r.direction());
    const double c = glm::dot(oc, oc) - radius * radius;
    const double discriminant = half_b * half_b - a * c;
    if (discriminant < 0) return false;
    const double sqrtd = std::sqrt(discriminant);
    double root = (-half_b - sqrtd) / a;
    if (root < t_min || t_max < root) {
      root = (-half_b + sqrtd) / a;
      if (root < t_min || t_max < root) return false;
    }
    rec.t = root;
    rec.p = r.at(rec.t);
    const vec3 outward_normal = (rec.p - center) / radius;
    rec.set_face_normal(r, outward_normal);
    return true;
  }

  point3 center;
  double radius;
};

// hittable_list.h
class hittable_list : public hittable {
 public:
  void add(std::shared_ptr<hittable> object) { objects.push_back(std::move(object)); }
  bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const override {
    hit_record temp_rec;
    bool hit_anything = false;
    double closest_so_far = t_max;
    for (const auto& object : objects) {
      if (object->hit(r, t_min, closest_so_far, temp_rec)) {
        hit_anything = true;
        closest_so_far = temp_rec.t;
        rec = temp_rec;
      }
    }
    return hit_anything;
  }

  std::vector<std::shared_ptr<hittable>> objects;
};

// main.cc
color ray_color(const ray& r, const hittable& world) {
  hit_record rec;
  if (world.hit(r, 0, std::numeric_limits<double>::infinity(), rec))
    return 0.5 * (rec.normal + color(1, 1, 1));
  const vec3 unit_direction = r.direction() / glm::length(r.direction());
  const double t = 0.5 * (unit_direction.y + 1.0);
  return (1.0 - t) * color(1.0, 1.0, 1.0) + t * color(0.5, 0.7, 1.0);
}

}  // namespace

struct book_ch6::world {
  hittable_list list;
};

book_ch6::book_ch6(const scene& s) : scene_(s), world_(std::make_unique<world>()) {
  for (const sphere& sp : s.spheres) world_->list.add(std::make_shared<book_sphere>(sp.center, sp.radius));
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
