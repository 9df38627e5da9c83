// The sky of a render with many samples per pixel, written once for a lane type (float and
// uint32_t, or vfloat and vuint) so that every backend computes the same bits. A miss adds
// u = d.y / |d| to the pixel's sky sum and 1 to its sky count; the sky's colour, affine in u, is
// applied once per pixel (kernels/scalar.h). 1/|d| is a bit-level first guess (within 3.5e-3)
// refined by two Newton steps of plain IEEE operations: a few float ulp, far below sample noise.
#pragma once
#include <cfloat>
#include <cstdint>
#include <cstring>

#include "sampling/sampler.h"

namespace raycast::sampling {

// The scalar lane type's operations, as the vector layers spell them (min: sampling/sampler.h).
inline uint32_t as_uint(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline float as_float(uint32_t u) {
  float x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
inline float max(float a, float b) { return a > b ? a : b; }

// 1 / sqrt(x) for a positive normal float x.
template <class F, class U>
inline F rsqrt_newton(F x) {
  F y = as_float(U(0x5f375a86u) - (as_uint(x) >> 1));
  const F h = x * F(0.5f);
  y = y * (F(1.5f) - (h * y) * y);
  return y * (F(1.5f) - (h * y) * y);
}

// u = d.y / |d|, clamped to [-1, 1], from d.y and n2 = |d|^2.
template <class F, class U>
inline F sky_u(F dy, F n2) {
  const F u = dy * rsqrt_newton<F, U>(max(n2, F(FLT_MIN)));
  return min(max(u, F(-1.0f)), F(1.0f));
}

}  // namespace raycast::sampling
