#include "scalar.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raycast {
namespace {

// 1/sqrt(x) from the hardware estimate refined by one Newton step,
// r' = r * (1.5 - (0.5 x * r) * r): the same estimate and order as the SSE2
// and AVX2 kernels' fast mode.
float rsqrt_nr(float x) {
#if defined(__SSE__) || defined(__x86_64__)
  const float r = _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
  const float h = 0.5f * x;
  return r * (1.5f - (h * r) * r);
#else
  return 1.0f / std::sqrt(x);
#endif
}

float clampf(float x, float lo, float hi) { return std::min(std::max(x, lo), hi); }

}  // namespace

void scalar_pixel(const float_scene& f, precision p, int64_t i, int64_t j, float out[3]) {
  const float u = f.width == 1 ? 0.5f : float(i) / f.wm1;
  const float v = f.height == 1 ? 0.5f : float(j) / f.hm1;
  float d[3];
  for (int k = 0; k < 3; ++k) d[k] = (f.corner[k] + u * f.horizontal[k]) + v * f.vertical[k];
  const float n2 = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
  float uy = 0.0f;
  if (n2 >= FLT_MIN) uy = p == precision::exact ? d[1] / std::sqrt(n2) : d[1] * rsqrt_nr(n2);
  const float t = clampf((uy + 1.0f) * 0.5f, 0.0f, 1.0f);
  for (int k = 0; k < 3; ++k)
    out[k] = clampf(t == 1.0f ? f.top[k] : f.bottom[k] + t * f.delta[k], f.lo[k], f.hi[k]);
}

void render_scalar(const float_scene& f, precision p, const image_band& band) {
  for (int64_t r = band.row_begin; r < band.row_end; ++r) {
    const int64_t j = f.height - 1 - r;
    unsigned char* row = band.row(r);
    for (int64_t i = 0; i < f.width; ++i) {
      float c[3];
      scalar_pixel(f, p, i, j, c);
      if (band.format == pixel_format::rgb8) {
        for (int k = 0; k < 3; ++k)
          row[3 * i + k] = static_cast<unsigned char>(int(clampf(c[k], 0.0f, 1.0f) * 255.999f));
      } else {
        std::memcpy(row + 12 * i, c, sizeof c);
      }
    }
  }
}

}  // namespace raycast
