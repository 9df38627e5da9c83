#include "kernels/float_scene.h"

#include <algorithm>
#include <cmath>

namespace raycast {

float_scene prepare_float_scene(const scene& s) {
  const camera& c = s.cam;
  float_scene f;
  f.width = c.image_width;
  f.height = c.image_height;
  f.last_col = float(c.image_width - 1);
  f.last_row = float(c.image_height - 1);
  f.mid_col = float(double(c.image_width - 1) / 2.0);
  f.mid_row = float(double(c.image_height - 1) / 2.0);
  const vec3 centre = -c.focal_length * c.axis_w;

  double m = 0.0;
  for (const vec3& v : {centre, c.horizontal, c.vertical})
    m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  int e = 0;
  std::frexp(m, &e);  // m = x * 2^e with x in [0.5, 1)
  const double scale = std::ldexp(1.0, -e);
  // Values below 2^-64 (camera components relative to the largest, and sky
  // colours) become 0. They cannot change a float result, but as denormals
  // somewhere in the arithmetic they could make the output depend on the
  // FTZ/DAZ bits; above 2^-64 no product or sum in scalar.h is denormal.
  const auto flush = [](double x) { return std::abs(x) < 0x1p-64 ? 0.0f : float(x); };
  for (int k = 0; k < 3; ++k) {
    f.centre[k] = flush(centre[k] * scale);
    f.horizontal[k] = flush(c.horizontal[k] * scale);
    f.vertical[k] = flush(c.vertical[k] * scale);
    f.bottom[k] = flush(s.sky.bottom[k]) + 0.0f;  // + 0: a -0 colour becomes +0
    f.top[k] = flush(s.sky.top[k]) + 0.0f;
    f.delta[k] = f.top[k] - f.bottom[k];
    const double half = 0.5 * (double(f.top[k]) - double(f.bottom[k]));
    f.fast_qa[k] = float(255.999 * half);
    f.fast_qb[k] = float(255.999 * (double(f.bottom[k]) + half));
    f.lo[k] = std::min(f.bottom[k], f.top[k]);
    f.hi[k] = std::max(f.bottom[k], f.top[k]);
  }
  f.axis_aligned_camera = f.horizontal[1] == 0 && f.horizontal[2] == 0 && f.vertical[0] == 0 &&
                   f.vertical[2] == 0;
  return f;
}

}  // namespace raycast
