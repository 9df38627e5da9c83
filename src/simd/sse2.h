// SSE2 (every x86-64): 8 float lanes as two __m128 halves. See README.md.
#pragma once
#include <emmintrin.h>

#include <cstdint>

#include "simd/inline.h"

namespace raycast::simd::sse2 {

// What this instruction set offers beyond the common vocabulary (README.md):
// none. The kernel falls back to plain stores.

// How many vfloats the register file holds (16 xmm registers, two per vfloat): the sphere kernel's
// sampled path takes two samples a pass where that is 16 or more.
inline constexpr int vfloats_in_registers = 8;

struct vmask {
  __m128 lo, hi;
};

struct vfloat {
  static constexpr int size = 8;
  __m128 lo, hi;
  vfloat() = default;
  RAYCAST_INLINE vfloat(__m128 l, __m128 h) : lo(l), hi(h) {}
  // Every lane s; implicit, as Embree's, so that kernels write (uy + 1.0f) * 0.5f.
  RAYCAST_INLINE vfloat(float s) : lo(_mm_set1_ps(s)), hi(lo) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return {_mm_loadu_ps(p), _mm_loadu_ps(p + 4)}; }
};

struct vint {
  __m128i lo, hi;
};

#define RAYCAST_SSE2_BINARY(name, op) \
  RAYCAST_INLINE vfloat name(vfloat a, vfloat b) { return {op(a.lo, b.lo), op(a.hi, b.hi)}; }
RAYCAST_SSE2_BINARY(operator+, _mm_add_ps)
RAYCAST_SSE2_BINARY(operator-, _mm_sub_ps)
RAYCAST_SSE2_BINARY(operator*, _mm_mul_ps)
RAYCAST_SSE2_BINARY(operator/, _mm_div_ps)
RAYCAST_SSE2_BINARY(min, _mm_min_ps)
RAYCAST_SSE2_BINARY(max, _mm_max_ps)
#undef RAYCAST_SSE2_BINARY

// IEEE negation (the sign bit flipped), as the scalar -x: -(+0) is -0.
RAYCAST_INLINE vfloat operator-(vfloat a) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  return {_mm_xor_ps(a.lo, sign), _mm_xor_ps(a.hi, sign)};
}
RAYCAST_INLINE void store(float* p, vfloat a) {
  _mm_storeu_ps(p, a.lo);
  _mm_storeu_ps(p + 4, a.hi);
}
RAYCAST_INLINE vmask operator==(vfloat a, vfloat b) { return {_mm_cmpeq_ps(a.lo, b.lo), _mm_cmpeq_ps(a.hi, b.hi)}; }
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
// Ordered comparisons (false where either lane is NaN); vmask{} is all false.
RAYCAST_INLINE vmask operator>=(vfloat a, vfloat b) { return {_mm_cmpge_ps(a.lo, b.lo), _mm_cmpge_ps(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator<=(vfloat a, vfloat b) { return {_mm_cmple_ps(a.lo, b.lo), _mm_cmple_ps(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator&(vmask a, vmask b) { return {_mm_and_ps(a.lo, b.lo), _mm_and_ps(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator|(vmask a, vmask b) { return {_mm_or_ps(a.lo, b.lo), _mm_or_ps(a.hi, b.hi)}; }
RAYCAST_INLINE bool any(vmask m) { return _mm_movemask_ps(_mm_or_ps(m.lo, m.hi)) != 0; }
RAYCAST_INLINE bool none(vmask m) { return !any(m); }
RAYCAST_INLINE bool all(vmask m) { return _mm_movemask_ps(_mm_and_ps(m.lo, m.hi)) == 0xf; }
RAYCAST_INLINE vmask operator!(vmask m) {
  const __m128 ones = _mm_castsi128_ps(_mm_set1_epi32(-1));
  return {_mm_xor_ps(m.lo, ones), _mm_xor_ps(m.hi, ones)};
}
// |a| with the sign of b, as std::copysign.
RAYCAST_INLINE vfloat copysign(vfloat a, vfloat b) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  return {_mm_or_ps(_mm_andnot_ps(sign, a.lo), _mm_and_ps(sign, b.lo)),
          _mm_or_ps(_mm_andnot_ps(sign, a.hi), _mm_and_ps(sign, b.hi))};
}
RAYCAST_INLINE __m128 blend(__m128 m, __m128 a, __m128 b) {  // m ? a : b, no SSE4.1 blendv
  return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) { return {blend(m.lo, a.lo, b.lo), blend(m.hi, a.hi, b.hi)}; }
RAYCAST_INLINE vfloat sqrt(vfloat a) { return {_mm_sqrt_ps(a.lo), _mm_sqrt_ps(a.hi)}; }
// No FMA on SSE2: a multiply and an add (or subtract), two roundings.
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) { return a * b + c; }
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) { return c - a * b; }
// 1/sqrt(x), hardware estimate: relative error below 1.5 * 2^-12.
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) { return {_mm_rsqrt_ps(x.lo), _mm_rsqrt_ps(x.hi)}; }
RAYCAST_INLINE vint to_int(vfloat a) { return {_mm_cvttps_epi32(a.lo), _mm_cvttps_epi32(a.hi)}; }
// Lanes in the opposite order (the mirrored pixels of a batch): each half
// reversed, and the halves swapped.
RAYCAST_INLINE vfloat reverse(vfloat a) {
  return {_mm_shuffle_ps(a.hi, a.hi, _MM_SHUFFLE(0, 1, 2, 3)),
          _mm_shuffle_ps(a.lo, a.lo, _MM_SHUFFLE(0, 1, 2, 3))};
}
RAYCAST_INLINE vint reverse(vint a) {
  return {_mm_shuffle_epi32(a.hi, _MM_SHUFFLE(0, 1, 2, 3)), _mm_shuffle_epi32(a.lo, _MM_SHUFFLE(0, 1, 2, 3))};
}
RAYCAST_INLINE vint splat_int(int32_t x) { return {_mm_set1_epi32(x), _mm_set1_epi32(x)}; }

// 8 pixels of RGB8, interleaved in registers: 12 bytes in each half.
struct rgb8_pack {
  __m128i lo, hi;
};

// 4 lanes of bytes -> 12 bytes r0 g0 b0 r1 ... No pshufb in SSE2: pack each
// dword as (r g b 0), squeeze the zero byte out of each 64-bit half with
// shifts, then close the gap between the halves.
RAYCAST_INLINE __m128i pack_rgb8_half(__m128i r, __m128i g, __m128i b) {
  const __m128i w = _mm_or_si128(r, _mm_or_si128(_mm_slli_epi32(g, 8), _mm_slli_epi32(b, 16)));
  const __m128i low3 = _mm_set1_epi64x(0x0000000000FFFFFFll);
  const __m128i next3 = _mm_set1_epi64x(0x0000FFFFFF000000ll);
  const __m128i six = _mm_or_si128(_mm_and_si128(w, low3), _mm_and_si128(_mm_srli_epi64(w, 8), next3));
  const __m128i lo_q = _mm_set_epi64x(0, -1);
  return _mm_or_si128(_mm_and_si128(six, lo_q), _mm_srli_si128(_mm_andnot_si128(lo_q, six), 2));
}
// Reversed puts the pixels in the opposite order (the mirrored batch).
template <bool Reversed = false>
RAYCAST_INLINE rgb8_pack pack_rgb8(vint r, vint g, vint b) {
  if constexpr (Reversed) {
    r = reverse(r);
    g = reverse(g);
    b = reverse(b);
  }
  return {pack_rgb8_half(r.lo, g.lo, b.lo), pack_rgb8_half(r.hi, g.hi, b.hi)};
}
RAYCAST_INLINE void store12(unsigned char* dst, __m128i twelve) {
  _mm_storel_epi64(reinterpret_cast<__m128i*>(dst), twelve);
  const int32_t tail = _mm_cvtsi128_si32(_mm_srli_si128(twelve, 8));
  __builtin_memcpy(dst + 8, &tail, 4);
}
RAYCAST_INLINE void store(unsigned char* dst, rgb8_pack p) {
  store12(dst, p.lo);
  store12(dst + 12, p.hi);
}

RAYCAST_INLINE void store_rgbf_half(float* dst, __m128 r, __m128 g, __m128 b) {
  const __m128 a = _mm_unpacklo_ps(r, g);                                  // r0 g0 r1 g1
  const __m128 c = _mm_shuffle_ps(b, r, _MM_SHUFFLE(1, 1, 0, 0));          // b0 b0 r1 r1
  _mm_storeu_ps(dst + 0, _mm_shuffle_ps(a, c, _MM_SHUFFLE(2, 0, 1, 0)));   // r0 g0 b0 r1
  const __m128 d = _mm_shuffle_ps(g, b, _MM_SHUFFLE(1, 1, 1, 1));          // g1 g1 b1 b1
  const __m128 e = _mm_shuffle_ps(r, g, _MM_SHUFFLE(2, 2, 2, 2));          // r2 r2 g2 g2
  _mm_storeu_ps(dst + 4, _mm_shuffle_ps(d, e, _MM_SHUFFLE(2, 0, 2, 0)));   // g1 b1 r2 g2
  const __m128 f = _mm_shuffle_ps(b, r, _MM_SHUFFLE(3, 3, 2, 2));          // b2 b2 r3 r3
  const __m128 h = _mm_shuffle_ps(g, b, _MM_SHUFFLE(3, 3, 3, 3));          // g3 g3 b3 b3
  _mm_storeu_ps(dst + 8, _mm_shuffle_ps(f, h, _MM_SHUFFLE(2, 0, 2, 0)));   // b2 r3 g3 b3
}
RAYCAST_INLINE void store_rgbf(float* dst, vfloat r, vfloat g, vfloat b) {
  store_rgbf_half(dst, r.lo, g.lo, b.lo);
  store_rgbf_half(dst + 12, r.hi, g.hi, b.hi);
}

// Unsigned 32-bit lanes for the samplers' counter-based hashes
// (scene/sampler.h): wrap-around + and *, xor, logical shifts.
struct vuint {
  __m128i lo, hi;
  vuint() = default;
  RAYCAST_INLINE vuint(__m128i l, __m128i h) : lo(l), hi(h) {}
  RAYCAST_INLINE vuint(uint32_t s) : lo(_mm_set1_epi32(int32_t(s))), hi(lo) {}
  // start, start + 1, ... in lane order.
  static RAYCAST_INLINE vuint iota(uint32_t start) {
    const __m128i s = _mm_set1_epi32(int32_t(start));
    return {_mm_add_epi32(s, _mm_setr_epi32(0, 1, 2, 3)), _mm_add_epi32(s, _mm_setr_epi32(4, 5, 6, 7))};
  }
};
// SSE2 has no 32-bit low multiply (SSE4.1's pmulld): two 32x32->64 multiplies
// of the even and odd lanes, their low halves interleaved.
RAYCAST_INLINE __m128i mullo32(__m128i a, __m128i b) {
  const __m128i even = _mm_mul_epu32(a, b);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
  return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                            _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
}
#define RAYCAST_SSE2_UINT(name, op) \
  RAYCAST_INLINE vuint name(vuint a, vuint b) { return {op(a.lo, b.lo), op(a.hi, b.hi)}; }
RAYCAST_SSE2_UINT(operator+, _mm_add_epi32)
RAYCAST_SSE2_UINT(operator-, _mm_sub_epi32)
RAYCAST_SSE2_UINT(operator*, mullo32)
RAYCAST_SSE2_UINT(operator^, _mm_xor_si128)
RAYCAST_SSE2_UINT(operator&, _mm_and_si128)
RAYCAST_SSE2_UINT(operator|, _mm_or_si128)
#undef RAYCAST_SSE2_UINT
RAYCAST_INLINE vuint operator>>(vuint a, int n) { return {_mm_srli_epi32(a.lo, n), _mm_srli_epi32(a.hi, n)}; }
RAYCAST_INLINE vuint operator<<(vuint a, int n) { return {_mm_slli_epi32(a.lo, n), _mm_slli_epi32(a.hi, n)}; }
// Lanes below 2^31, as floats (exact below 2^24).
RAYCAST_INLINE vfloat to_float(vuint a) { return {_mm_cvtepi32_ps(a.lo), _mm_cvtepi32_ps(a.hi)}; }

// The bits of a float as an unsigned integer, and back.
RAYCAST_INLINE vuint as_uint(vfloat a) { return {_mm_castps_si128(a.lo), _mm_castps_si128(a.hi)}; }
RAYCAST_INLINE vfloat as_float(vuint a) { return {_mm_castsi128_ps(a.lo), _mm_castsi128_ps(a.hi)}; }

}  // namespace raycast::simd::sse2
