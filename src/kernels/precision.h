// How the float renderers compute y / |d| (kernels/scalar.h).
#pragma once
#include <cstdint>

namespace raycast {

enum class precision : uint8_t {
  exact,  // IEEE sqrt and divide: every backend gives the same bits
  fast,   // reciprocal square root estimate + one Newton step
};

}  // namespace raycast
