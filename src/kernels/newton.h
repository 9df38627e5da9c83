// Fast mode's biased Newton step on the estimate r of 1 / sqrt(n2) (kernels/scalar.h):
//   y / |d| = (y * r) * (fast_nr_a - ((n2 * r) * r) * fast_nr_b)
#pragma once

namespace raycast {

inline constexpr float fast_nr_a = 1.5f * (1.0f + 0x1p-20f);
inline constexpr float fast_nr_b = 0.5f * (1.0f + 0x1p-20f);

}  // namespace raycast
