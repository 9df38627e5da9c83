// The vector of light/: four floats (or int32s) a lane each, in GCC's and
// clang's vector types. light/ is compiled once, for the build's baseline:
// these are SSE2 registers on x86-64 and NEON ones on AArch64, with the
// same float operations lane by lane as one at a time (no FMA: the rooms
// build with -ffp-contract=off), so a lane's result is the scalar code's bits.
#pragma once
#include <cstdint>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace raycast {
namespace lanes {

constexpr int width = 4;
typedef float fvec __attribute__((vector_size(width * sizeof(float))));
typedef int32_t ivec __attribute__((vector_size(width * sizeof(float))));  // also masks: 0 or -1 a lane
typedef uint32_t uvec __attribute__((vector_size(width * sizeof(float))));

// a where m is set, b elsewhere.
inline fvec pick(ivec m, fvec a, fvec b) { return fvec((ivec(a) & m) | (ivec(b) & ~m)); }
// Each lane's square root (sqrtps on SSE2: correctly rounded, as std::sqrt).
inline fvec sqrt(fvec x) {
  for (int l = 0; l < width; ++l) x[l] = __builtin_sqrtf(x[l]);
  return x;
}
// Bit l set where lane l of m is: SSE2's movmskps (the lanes' sign bits),
// elsewhere each lane's weight summed.
inline uint32_t bits_of(ivec m) {
  static_assert(width == 4, "one weight a lane below");
#if defined(__SSE2__)
  return uint32_t(_mm_movemask_ps(__m128(m)));
#else
  const uvec w = uvec(m) & uvec{1, 2, 4, 8};
  return (w[0] | w[1]) | (w[2] | w[3]);
#endif
}

}  // namespace lanes
}  // namespace raycast
