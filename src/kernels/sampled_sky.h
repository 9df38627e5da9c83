// The sky of a render with many samples per pixel, written once for a lane
// type (float and uint32_t for the scalar renderer, vfloat and vuint for the
// kernels) so that every backend computes the same bits.
//
// A sample that hits no sphere adds u = d.y / |d| to the pixel's sky sum and
// 1 to its sky count; the sky's colour, affine in u (bottom + t delta with
// t = (u + 1) / 2 = sky_mid + u * sky_half), is applied once per pixel:
//   pixel = ((flat + (normals + normal count) 0.5) + (sky count * sky_mid + sky sum * sky_half)) / N
// (kernels/scalar.h: the hits' sums). u comes without the divider: 1/|d| is a bit-level
// first guess refined by two Newton steps -- plain IEEE multiplies and
// subtractions, so every instruction set gives the same bits -- accurate to
// a few float ulp (the first guess is within 3.5e-3, each step squares
// that), far below the noise of any sample count.
#pragma once
#include <cfloat>
#include <cstdint>
#include <cstring>

#include "sampling/sampler.h"

namespace raycast::sampling {

// The scalar lane type's operations, as the vector layers spell them (min:
// scene/sampler.h).
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
