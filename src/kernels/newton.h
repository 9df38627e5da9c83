// Fast mode's Newton step on the reciprocal-square-root estimate r of n2:
//   y / |d| = (y * r) * (fast_nr_a - ((n2 * r) * r) * fast_nr_b)
// biased up by 2^-20 so that straight up and down land on exactly +-1
// (kernels/scalar.h); the sky kernel's fast mode on every target.
#pragma once

namespace raycast {

inline constexpr float fast_nr_a = 1.5f * (1.0f + 0x1p-20f);
inline constexpr float fast_nr_b = 0.5f * (1.0f + 0x1p-20f);

}  // namespace raycast
