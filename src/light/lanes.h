// The vector of light/: four floats (or int32s), a lane each, in GCC's and
// clang's vector types. light/ is compiled for the build's baseline: these
// are SSE2 registers on x86-64 and NEON ones on AArch64, with the same float
// operations lane by lane as one at a time (no FMA: the rooms build with
// -ffp-contract=off), so a lane's result is the scalar code's bits.
//
// On x86-64 the grid's walk in lanes (grid_lanes.cpp) is compiled a second
// time, with -mavx2 and RAYCAST_LIGHT_LANES=8: eight lanes, a hit's eight AO
// rays in one vector, taken where the CPU runs AVX2 (sphere_grid::occluded).
// The same float operations lane by lane again, so the same bits. Each
// width's vocabulary lives in its own inline namespace (w4, w8), so that the
// two compilations share no function: a helper the AVX2 one leaves out of
// line cannot stand in for the baseline's.
#pragma once
#include <cstdint>

#if !defined(RAYCAST_LIGHT_LANES) || RAYCAST_LIGHT_LANES == 4
#define RAYCAST_LANES_NAMESPACE w4
#define RAYCAST_LANES_WIDTH 4
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif
#elif RAYCAST_LIGHT_LANES == 8 && defined(__AVX__)
#define RAYCAST_LANES_NAMESPACE w8
#define RAYCAST_LANES_WIDTH 8
#include <immintrin.h>
#else
#error "RAYCAST_LIGHT_LANES: 4, or 8 with AVX2"
#endif

namespace raycast {
namespace lanes {
inline namespace RAYCAST_LANES_NAMESPACE {

constexpr int width = RAYCAST_LANES_WIDTH;
typedef float fvec __attribute__((vector_size(width * sizeof(float))));
typedef int32_t ivec __attribute__((vector_size(width * sizeof(float))));  // also masks: 0 or -1 a lane
typedef uint32_t uvec __attribute__((vector_size(width * sizeof(float))));

// a where m is set, b elsewhere.
inline fvec pick(ivec m, fvec a, fvec b) { return fvec((ivec(a) & m) | (ivec(b) & ~m)); }
// x in every lane.
inline fvec splat(float x) { return x - fvec{}; }  // x - +0 is x, -0 included
// Each lane's square root (sqrtps: correctly rounded, as std::sqrt).
inline fvec sqrt(fvec x) {
  for (int l = 0; l < width; ++l) x[l] = __builtin_sqrtf(x[l]);
  return x;
}
// Bit l set where lane l of m is: SSE2's and AVX's movmskps (the lanes'
// sign bits), elsewhere each lane's weight summed.
inline uint32_t bits_of(ivec m) {
#if RAYCAST_LANES_WIDTH == 8
  return uint32_t(_mm256_movemask_ps(__m256(m)));
#elif defined(__SSE2__) && RAYCAST_LANES_WIDTH == 4
  return uint32_t(_mm_movemask_ps(__m128(m)));
#else
  static_assert(width == 4, "one weight a lane below");
  const uvec w = uvec(m) & uvec{1, 2, 4, 8};
  return (w[0] | w[1]) | (w[2] | w[3]);
#endif
}

// sphere_grid::blocks() in lanes: whether the segment o + t d[.][l], t in
// [0, tmax], meets the solid ball of the sphere s[.][l] (centre x y z,
// radius), lane by lane: the same float operations in the same order, so
// the same bits as blocks() (a negative gap's root is taken of 0 instead,
// in a lane whose m2 <= r2 is false, so it cannot change the lane's result).
inline ivec blocks_in_lanes(const float o[3], const fvec d[3], const fvec s[4], float tmax) {
  const fvec ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const fvec r2 = s[3] * s[3];
  const fvec b = (ox * d[0] + oy * d[1]) + oz * d[2];
  const fvec vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const fvec m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2;
  const fvec near = -b - sqrt(pick(ivec(gap > 0.0f), gap, fvec{}));
  return ivec((ox * ox + oy * oy) + oz * oz <= r2) | (ivec(b < 0.0f) & ivec(m2 <= r2) & ivec(near <= tmax));
}

}  // inline namespace RAYCAST_LANES_NAMESPACE
}  // namespace lanes
}  // namespace raycast
