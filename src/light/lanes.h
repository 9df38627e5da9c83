// The vectors of light/: GCC's and clang's vector types, a lane a float (or
// an int32 mask, 0 or -1). Three compilations of the light's kernels
// (light/kernels.h) each see one instruction set: the build's baseline
// (SSE2 on x86-64, NEON on AArch64: four floats a register), AVX2 (eight)
// and AVX-512 (sixteen). The data they read is laid out the same for all:
// a node's eight children (f8), a block of sixteen spheres (f16); each
// compilation splits those into its own registers. The same float operations
// lane by lane (no FMA: the rooms build with -ffp-contract=off), so a lane's
// result is the one-at-a-time code's bits at every width.
//
// Each width's vocabulary lives in its own inline namespace (w4, w8, w16), so
// that the compilations share no function: a helper the AVX-512 one leaves
// out of line cannot stand in for the baseline's.
#pragma once
#include <cstdint>

#include "simd/inline.h"

#if !defined(RAYCAST_LIGHT_LANES) || RAYCAST_LIGHT_LANES == 4
#define RAYCAST_LANES_NAMESPACE w4
#define RAYCAST_LANES_WIDTH 4
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#elif RAYCAST_LIGHT_LANES == 8 && defined(__AVX2__)
#define RAYCAST_LANES_NAMESPACE w8
#define RAYCAST_LANES_WIDTH 8
#include <immintrin.h>
#elif RAYCAST_LIGHT_LANES == 16 && defined(__AVX512F__)
#define RAYCAST_LANES_NAMESPACE w16
#define RAYCAST_LANES_WIDTH 16
#include <immintrin.h>
#else
#error "RAYCAST_LIGHT_LANES: 4, 8 with AVX2, or 16 with AVX-512"
#endif

namespace raycast {
namespace lanes {
inline namespace RAYCAST_LANES_NAMESPACE {

constexpr int width = RAYCAST_LANES_WIDTH;  // floats a register of this compilation
typedef float f4 __attribute__((vector_size(16)));
typedef int32_t i4 __attribute__((vector_size(16)));
typedef float f8 __attribute__((vector_size(32)));
typedef int32_t i8 __attribute__((vector_size(32)));
typedef float f16 __attribute__((vector_size(64)));
typedef int32_t i16 __attribute__((vector_size(64)));

// Unaligned loads of eight and sixteen floats (as vectors of the same types:
// a load through memcpy costs GCC a store and a reload).
typedef float f8_unaligned __attribute__((vector_size(32), aligned(4), may_alias));
typedef float f16_unaligned __attribute__((vector_size(64), aligned(4), may_alias));
RAYCAST_INLINE f8 load8(const float* p) { return *reinterpret_cast<const f8_unaligned*>(p); }
RAYCAST_INLINE f16 load16(const float* p) { return *reinterpret_cast<const f16_unaligned*>(p); }

// Each lane's square root (sqrtps: correctly rounded, as std::sqrt).
template <class F>
RAYCAST_INLINE F sqrt(F x) {
  for (int l = 0; l < int(sizeof(F) / sizeof(float)); ++l) x[l] = __builtin_sqrtf(x[l]);
  return x;
}

// This compilation's own register (fw: width floats) and the mask of each
// vector type (f8's is i8).
#if RAYCAST_LANES_WIDTH == 16
typedef f16 fw;
typedef i16 iw;
#elif RAYCAST_LANES_WIDTH == 8
typedef f8 fw;
typedef i8 iw;
#else
typedef f4 fw;
typedef i4 iw;
#endif
template <class F> struct mask_of;
template <> struct mask_of<f4> { typedef i4 type; };
template <> struct mask_of<f8> { typedef i8 type; };
template <> struct mask_of<f16> { typedef i16 type; };
template <class F> using mask_t = typename mask_of<F>::type;

// Comparisons lane by lane (-1 where true), max and min. GCC lowers a
// comparison (and a ?: on its result) of vectors wider than the
// compilation's registers one lane at a time, a scalar compare and a set a
// lane: an f16 compare in the AVX2 compilation, an f8 one in the
// baseline's, made the AVX2 frame's AO four times the AVX-512 one's. So a
// wider vector is worked on in register-wide pieces (the memcpy moves no
// data: the pieces are the registers that hold it).
template <class R, class Op, class F>
RAYCAST_INLINE R in_pieces(F a, F b) {
  if constexpr (sizeof(F) <= sizeof(fw)) {
    return R(Op{}(a, b));
  } else {
    constexpr int k = int(sizeof(F) / sizeof(fw));
    typedef decltype(Op{}(fw{}, fw{})) piece;
    fw pa[k], pb[k];
    piece r[k];
    __builtin_memcpy(pa, &a, sizeof a);
    __builtin_memcpy(pb, &b, sizeof b);
    for (int j = 0; j < k; ++j) r[j] = Op{}(pa[j], pb[j]);
    R out;
    __builtin_memcpy(&out, r, sizeof out);
    return out;
  }
}
struct less_op { template <class W> RAYCAST_INLINE auto operator()(W a, W b) const { return a < b; } };
struct less_equal_op { template <class W> RAYCAST_INLINE auto operator()(W a, W b) const { return a <= b; } };
struct max_op { template <class W> RAYCAST_INLINE W operator()(W a, W b) const { return a > b ? a : b; } };  // maxps: b where either is NaN
struct min_op { template <class W> RAYCAST_INLINE W operator()(W a, W b) const { return a < b ? a : b; } };
template <class F> RAYCAST_INLINE mask_t<F> lt(F a, F b) { return in_pieces<mask_t<F>, less_op>(a, b); }
template <class F> RAYCAST_INLINE mask_t<F> le(F a, F b) { return in_pieces<mask_t<F>, less_equal_op>(a, b); }
// Against one number (s - F{} is s in every lane, -0 and NaN included).
template <class F> RAYCAST_INLINE mask_t<F> lt(F a, float s) { return lt(a, s - F{}); }
template <class F> RAYCAST_INLINE mask_t<F> le(F a, float s) { return le(a, s - F{}); }
template <class F> RAYCAST_INLINE mask_t<F> ge(F a, float s) { return le(s - F{}, a); }
template <class F> RAYCAST_INLINE F max(F a, F b) { return in_pieces<F, max_op>(a, b); }
template <class F> RAYCAST_INLINE F min(F a, F b) { return in_pieces<F, min_op>(a, b); }

// Bit l set where lane l of m is (its sign bit): movmskps on x86, each
// lane's weight summed elsewhere.
RAYCAST_INLINE uint32_t bits_of(i4 m) {
#if defined(__SSE2__)
  return uint32_t(_mm_movemask_ps(__m128(m)));
#else
  const i4 w = m & i4{1, 2, 4, 8};
  return uint32_t((w[0] | w[1]) | (w[2] | w[3]));
#endif
}
RAYCAST_INLINE uint32_t bits_of(i8 m) {
#if RAYCAST_LANES_WIDTH >= 8
  return uint32_t(_mm256_movemask_ps(__m256(m)));
#else
  i4 h[2];
  __builtin_memcpy(h, &m, sizeof m);
  return bits_of(h[0]) | bits_of(h[1]) << 4;
#endif
}
RAYCAST_INLINE uint32_t bits_of(i16 m) {
#if RAYCAST_LANES_WIDTH == 16
  return uint32_t(_mm512_cmplt_epi32_mask(__m512i(m), _mm512_setzero_si512()));
#else
  i8 h[2];
  __builtin_memcpy(h, &m, sizeof m);
  return bits_of(h[0]) | bits_of(h[1]) << 8;
#endif
}

// Whether the segment o + t d, t in [0, tmax], meets the solid ball of each
// lane's sphere (centre x y z, radius r): a start inside it, or the near root
// -b - sqrt(gap) of a ball ahead within tmax, from Hearn and Baker's squared
// distance m2 of the line from the centre (no cancellation against
// |o - c|^2), gap = r^2 - m2. The root is compared squared: -b - tmax <= 0,
// or its square at most gap (no square root; unbounded rays compare
// -infinity). The one test of every occlusion query (light/README.md), in
// the same float operations in the same order lane by lane, so the same
// bits at every width and in secondary.cpp's one-ray form.
template <class F, class I>
RAYCAST_INLINE I blocks(const float o[3], const F d[3], const F s[4], float tmax) {
  const F ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const F r2 = s[3] * s[3];
  const F b = (ox * d[0] + oy * d[1]) + oz * d[2];
  const F vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const F m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2, beyond = -b - tmax;
  const I near = le(beyond, 0.0f) | le(beyond * beyond, gap);
  return le((ox * ox + oy * oy) + oz * oz, r2) | (lt(b, 0.0f) & le(m2, r2) & near);
}

// The same ball met by the segment t in [t0, tmax] of a ray that starts
// outside it (the far field's: every ball that holds the start is in the
// near field's list): the line's roots -b -+ sqrt(gap), the near one within
// tmax and the far one past t0, both compared squared; and a start inside
// where t0 is 0.
template <class F, class I>
RAYCAST_INLINE I blocks_beyond(const float o[3], const F d[3], const F s[4], float t0, float tmax) {
  const F ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const F r2 = s[3] * s[3];
  const F b = (ox * d[0] + oy * d[1]) + oz * d[2];
  const F vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const F m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2, beyond = -b - tmax, before = t0 + b;
  const I near = le(beyond, 0.0f) | le(beyond * beyond, gap), far = le(before, 0.0f) | le(before * before, gap);
  const I inside = le((ox * ox + oy * oy) + oz * oz, r2) & (t0 <= 0.0f ? ~I{} : I{});
  return inside | (le(m2, r2) & near & far);
}

}  // inline namespace RAYCAST_LANES_NAMESPACE
}  // namespace lanes
}  // namespace raycast
