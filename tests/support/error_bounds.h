// The float renderers' documented error bounds against the double reference,
// in linear colour, as a multiple of S = max(1, |bottom|, |top|) over all
// channels (src/kernels/README.md, "The sky: numerics contract";
// kernels/scalar.h gives the operations).
// The lerp multiplies t's error by |top - bottom| <= 2 S; t itself is within
// 6e-7 (exact) and 1.2e-6 (fast: the 2^-20 bias plus the estimate) of the
// reference. 8-bit output is within 1 LSB in both modes.
#pragma once
#include "kernels/precision.h"

namespace raycast {

inline constexpr double exact_error_bound = 1.5e-6;
inline constexpr double fast_error_bound = 3e-6;

inline constexpr double error_bound(precision p) {
  return p == precision::exact ? exact_error_bound : fast_error_bound;
}

}  // namespace raycast
