// kernels/scalar.h's exact sky, for the sky kernel and the sphere kernel's misses.
#pragma once
#include <cfloat>

#include "kernels/target.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

RAYCAST_INLINE vfloat exact_uy(vfloat y, vfloat n2) { return y / sqrt(max(n2, FLT_MIN)); }

// t = (uy + 1) 0.5; |y| <= sqrt(fl(y^2)) <= |d|, so scalar.h's clamp of t changes nothing.
RAYCAST_INLINE vfloat sky_t(vfloat uy) { return (uy + 1.0f) * 0.5f; }

// The sky's colours in registers, loaded once per call (image stores may alias anything).
struct sky_colors {
  vfloat bottom[3], top[3], delta[3], lo[3], hi[3];
  explicit sky_colors(const float_scene& s) {
    for (int k = 0; k < 3; ++k)
      bottom[k] = s.bottom[k], top[k] = s.top[k], delta[k] = s.delta[k], lo[k] = s.lo[k], hi[k] = s.hi[k];
  }
  // Channel k: clamp(t == 1 ? top : bottom + t delta, lo, hi); the lerp is monotone in t, so with
  // exact end points (shortcut `clamps`) the select and the clamp are no-ops.
  template <bool ExactEnds>
  RAYCAST_INLINE vfloat channel(int k, vfloat t) const {
    const vfloat c = bottom[k] + t * delta[k];
    if constexpr (ExactEnds) return c;
    return clamp(select(t == 1.0f, top[k], c), lo[k], hi[k]);
  }
};

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
