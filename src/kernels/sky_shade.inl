// The sky's colour in the kernels, written once for the sky kernel
// (sky_kernel.cpp) and the sphere kernel's misses (sphere_shade.inl):
// kernels/scalar.h's exact sky.
#pragma once
#include <cfloat>

#include "kernels/target.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// Exact mode: uy = y / |d|, |d| = sqrt(max(n2, FLT_MIN)) (scalar.h).
RAYCAST_INLINE vfloat exact_uy(vfloat y, vfloat n2) { return y / sqrt(max(n2, FLT_MIN)); }

// t = (uy + 1) 0.5. Since |y| <= sqrt(fl(y^2)) <= |d|, t is in [0, 1]
// already: scalar.h's clamp of t cannot change it and is left out.
RAYCAST_INLINE vfloat sky_t(vfloat uy) { return (uy + 1.0f) * 0.5f; }

// The sky's colours in registers, loaded once per call (stores to the image
// may alias anything, so nothing is re-read from the scene per batch).
struct sky_colors {
  vfloat bottom[3], top[3], delta[3], lo[3], hi[3];
  explicit sky_colors(const float_scene& s) {
    for (int k = 0; k < 3; ++k) {
      bottom[k] = s.bottom[k];
      top[k] = s.top[k];
      delta[k] = s.delta[k];
      lo[k] = s.lo[k];
      hi[k] = s.hi[k];
    }
  }
  // Channel k: clamp(t == 1 ? top : bottom + t delta, lo, hi). The lerp is
  // monotone in t, so when its end points are exact (ExactEnds: shortcut
  // `clamps`) the select and the clamp are no-ops and are left out.
  template <bool ExactEnds>
  RAYCAST_INLINE vfloat channel(int k, vfloat t) const {
    const vfloat c = bottom[k] + t * delta[k];
    if constexpr (ExactEnds) return c;
    return clamp(select(t == 1.0f, top[k], c), lo[k], hi[k]);
  }
};

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
