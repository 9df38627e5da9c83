// The sampled path's sky (kernels/scalar.h): a miss adds u = d.y / |d| to the pixel's sky sum, with
// 1/|d| a bit-level first guess (within 3.5e-3) refined by two Newton steps of plain IEEE
// operations, so every backend computes the same bits (a few ulp, far below sample noise).
#pragma once
#include <cfloat>
#include <cstdint>

#include "sampling/sampler.h"

namespace raycast::sampling {

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
