#include "reference/reference.h"

#include <cfloat>
#include <cmath>
#include <cstring>

namespace raycast {
namespace {

// Rounds to float; a result below the smallest normal float becomes 0 (as the
// float renderers' colours do), so that the FTZ bit cannot change the output.
float to_float(double c) { return std::abs(c) < double(FLT_MIN) ? 0.0f : float(c); }

}  // namespace

color reference_pixel(const scene& s, int64_t i, int64_t j) {
  const camera& cam = s.cam;
  const ray r = cam.get_ray(cam.u_of(i), cam.v_of(j));
  return ray_color(r, s.sky);
}

void render_reference(const scene& s, const image_band& band) {
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  for (int64_t r = band.row_begin; r < band.row_end; ++r) {
    const int64_t j = H - 1 - r;
    unsigned char* row = band.row(r);
    for (int64_t i = 0; i < W; ++i) {
      const color c = reference_pixel(s, i, j);
      if (band.format == pixel_format::rgb8) {
        row[3 * i + 0] = to_byte(c.r);
        row[3 * i + 1] = to_byte(c.g);
        row[3 * i + 2] = to_byte(c.b);
      } else {
        const float f[3] = {to_float(c.r), to_float(c.g), to_float(c.b)};
        std::memcpy(row + 12 * i, f, sizeof f);
      }
    }
  }
}

}  // namespace raycast
