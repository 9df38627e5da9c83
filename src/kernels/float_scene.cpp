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

  // Per-sphere constants in double, each rounded to float once
  // (kernels/float_spheres.h).
  float_spheres& sp = f.spheres;
  for (const sphere& b : s.spheres) {
    const vec3 fo = c.origin - b.center;
    const double cc = (fo.x * fo.x + fo.y * fo.y + fo.z * fo.z) - b.radius * b.radius;
    sp.fx.push_back(float(fo.x));
    sp.fy.push_back(float(fo.y));
    sp.fz.push_back(float(fo.z));
    sp.c.push_back(float(cc));
    sp.r2.push_back(float(b.radius * b.radius));
    sp.inv_r.push_back(float(1.0 / b.radius));
    const bool flat = b.shade == shading::flat;
    sp.red.push_back(flat ? flush(b.flat_color.r) + 0.0f : 0.0f);
    sp.green.push_back(flat ? flush(b.flat_color.g) + 0.0f : 0.0f);
    sp.blue.push_back(flat ? flush(b.flat_color.b) + 0.0f : 0.0f);
    sp.flat.push_back(flat ? 1.0f : 0.0f);
    sp.any_flat = sp.any_flat || flat;
    sp.any_normal = sp.any_normal || !flat;
  }
  return f;
}

size_t spheres_near_row(const float_scene& f, float sv, uint32_t* out) {
  const float_spheres& sp = f.spheres;
  size_t count = 0;
  // The plane's normal, a x h with a = centre + sv * vertical (as scalar.h's
  // direction, in double).
  double a[3], h[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = double(f.centre[k]) + double(sv) * double(f.vertical[k]);
    h[k] = double(f.horizontal[k]);
  }
  const double n[3] = {a[1] * h[2] - a[2] * h[1], a[2] * h[0] - a[0] * h[2], a[0] * h[1] - a[1] * h[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.0) || !std::isfinite(len)) {  // a degenerate row: keep every sphere
    for (uint32_t k = 0; k < uint32_t(sp.size()); ++k) out[count++] = k;
    return count;
  }
  for (uint32_t k = 0; k < uint32_t(sp.size()); ++k) {
    const double fx = sp.fx[k], fy = sp.fy[k], fz = sp.fz[k];
    const double dist = std::abs(fx * n[0] + fy * n[1] + fz * n[2]) / len;
    const double r = std::sqrt(double(sp.r2[k]));
    const double f_len = std::sqrt(fx * fx + fy * fy + fz * fz);
    if (!(dist > r + 1e-4 * (f_len + r))) out[count++] = k;  // NaN: kept
  }
  return count;
}

}  // namespace raycast
