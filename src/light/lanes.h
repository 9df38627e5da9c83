// The vector of light/: four floats (or int32s) a lane each, in GCC's and
// clang's vector types. light/ is compiled once, for the build's baseline:
// these are SSE2 registers on x86-64 and NEON ones on AArch64, with the
// same float operations lane by lane as one at a time (no FMA: the rooms
// build with -ffp-contract=off), so a lane's result is the scalar code's bits.
#pragma once
#include <cstdint>

namespace raycast {
namespace lanes {

constexpr int width = 4;
typedef float fvec __attribute__((vector_size(width * sizeof(float))));
typedef int32_t ivec __attribute__((vector_size(width * sizeof(float))));  // also masks: 0 or -1 a lane
typedef uint32_t uvec __attribute__((vector_size(width * sizeof(float))));

// a where m is set, b elsewhere.
inline fvec pick(ivec m, fvec a, fvec b) { return fvec((ivec(a) & m) | (ivec(b) & ~m)); }
// Bit l set where lane l of m is.
inline uint32_t bits_of(ivec m) {
  uint32_t b = 0;
  for (int l = 0; l < width; ++l) b |= uint32_t(m[l] & 1) << l;
  return b;
}

}  // namespace lanes
}  // namespace raycast
