// SSE2 (every x86-64): 8 float lanes as two __m128 halves (two_halves.inl). See README.md.
#pragma once
#include <emmintrin.h>

#include <cstdint>

#include "simd/inline.h"

namespace raycast::simd::sse2 {

namespace half {
using f = __m128;
using i = __m128i;
using u = __m128i;
using m = __m128;
inline constexpr int registers = 16;  // xmm0-15
RAYCAST_INLINE f splat(float s) { return _mm_set1_ps(s); }
RAYCAST_INLINE f load(const float* p) { return _mm_loadu_ps(p); }
RAYCAST_INLINE void store(float* p, f a) { _mm_storeu_ps(p, a); }
RAYCAST_INLINE f add(f a, f b) { return _mm_add_ps(a, b); }
RAYCAST_INLINE f sub(f a, f b) { return _mm_sub_ps(a, b); }
RAYCAST_INLINE f mul(f a, f b) { return _mm_mul_ps(a, b); }
RAYCAST_INLINE f div(f a, f b) { return _mm_div_ps(a, b); }
RAYCAST_INLINE f min(f a, f b) { return _mm_min_ps(a, b); }
RAYCAST_INLINE f max(f a, f b) { return _mm_max_ps(a, b); }
RAYCAST_INLINE f neg(f a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
RAYCAST_INLINE f copysign(f a, f b) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  return _mm_or_ps(_mm_andnot_ps(sign, a), _mm_and_ps(sign, b));
}
RAYCAST_INLINE m eq(f a, f b) { return _mm_cmpeq_ps(a, b); }
RAYCAST_INLINE m ge(f a, f b) { return _mm_cmpge_ps(a, b); }
RAYCAST_INLINE m le(f a, f b) { return _mm_cmple_ps(a, b); }
RAYCAST_INLINE m and_mask(m a, m b) { return _mm_and_ps(a, b); }
RAYCAST_INLINE m or_mask(m a, m b) { return _mm_or_ps(a, b); }
RAYCAST_INLINE m not_mask(m a) { return _mm_xor_ps(a, _mm_castsi128_ps(_mm_set1_epi32(-1))); }
RAYCAST_INLINE bool any(m a) { return _mm_movemask_ps(a) != 0; }
RAYCAST_INLINE bool all(m a) { return _mm_movemask_ps(a) == 0xf; }
// m ? a : b, without SSE4.1's blendv.
RAYCAST_INLINE f select(m k, f a, f b) { return _mm_or_ps(_mm_and_ps(k, a), _mm_andnot_ps(k, b)); }
RAYCAST_INLINE f sqrt(f a) { return _mm_sqrt_ps(a); }
// No FMA on SSE2: a multiply and an add (or subtract), two roundings.
RAYCAST_INLINE f madd(f a, f b, f c) { return _mm_add_ps(_mm_mul_ps(a, b), c); }
RAYCAST_INLINE f nmadd(f a, f b, f c) { return _mm_sub_ps(c, _mm_mul_ps(a, b)); }
// 1/sqrt(x), hardware estimate: relative error below 1.5 * 2^-12.
RAYCAST_INLINE f rsqrt_est(f x) { return _mm_rsqrt_ps(x); }
RAYCAST_INLINE i to_int(f a) { return _mm_cvttps_epi32(a); }
RAYCAST_INLINE f reverse(f a) { return _mm_shuffle_ps(a, a, _MM_SHUFFLE(0, 1, 2, 3)); }
RAYCAST_INLINE i reverse(i a) { return _mm_shuffle_epi32(a, _MM_SHUFFLE(0, 1, 2, 3)); }
RAYCAST_INLINE i splat_int(int32_t x) { return _mm_set1_epi32(x); }
RAYCAST_INLINE u splat_u(uint32_t s) { return _mm_set1_epi32(int32_t(s)); }
RAYCAST_INLINE u iota(uint32_t start) { return _mm_add_epi32(splat_u(start), _mm_setr_epi32(0, 1, 2, 3)); }
RAYCAST_INLINE u add_u(u a, u b) { return _mm_add_epi32(a, b); }
RAYCAST_INLINE u sub_u(u a, u b) { return _mm_sub_epi32(a, b); }
// No pmulld: two 32x32->64 multiplies of the even and odd lanes, their low halves interleaved.
RAYCAST_INLINE u mul_u(u a, u b) {
  const __m128i even = _mm_mul_epu32(a, b);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
  return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                            _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
}
RAYCAST_INLINE u xor_u(u a, u b) { return _mm_xor_si128(a, b); }
RAYCAST_INLINE u and_u(u a, u b) { return _mm_and_si128(a, b); }
RAYCAST_INLINE u or_u(u a, u b) { return _mm_or_si128(a, b); }
RAYCAST_INLINE u shr(u a, int n) { return _mm_srli_epi32(a, n); }
RAYCAST_INLINE u shl(u a, int n) { return _mm_slli_epi32(a, n); }
RAYCAST_INLINE f to_float(u a) { return _mm_cvtepi32_ps(a); }
RAYCAST_INLINE u as_uint(f a) { return _mm_castps_si128(a); }
RAYCAST_INLINE f as_float(u a) { return _mm_castsi128_ps(a); }
// Unsigned: a signed compare with the top bits flipped.
RAYCAST_INLINE m gt_u(u a, u b) {
  const __m128i top = _mm_set1_epi32(INT32_MIN);
  return _mm_castsi128_ps(_mm_cmpgt_epi32(_mm_xor_si128(a, top), _mm_xor_si128(b, top)));
}
RAYCAST_INLINE u select_u(m k, u a, u b) {
  const __m128i km = _mm_castps_si128(k);
  return _mm_or_si128(_mm_and_si128(km, a), _mm_andnot_si128(km, b));
}
}  // namespace half

#include "simd/two_halves.inl"

// 8 pixels of RGB8, interleaved in registers: 12 bytes in each half.
struct rgb8_pack {
  __m128i lo, hi;
};

// 4 lanes of bytes -> 12 bytes r0 g0 b0 r1 ... (no pshufb): each dword as (r g b 0), the zero
// byte squeezed out of each 64-bit half with shifts, then the gap between the halves closed.
RAYCAST_INLINE __m128i pack_rgb8_half(__m128i r, __m128i g, __m128i b) {
  const __m128i w = _mm_or_si128(r, _mm_or_si128(_mm_slli_epi32(g, 8), _mm_slli_epi32(b, 16)));
  const __m128i low3 = _mm_set1_epi64x(0x0000000000FFFFFFll);
  const __m128i next3 = _mm_set1_epi64x(0x0000FFFFFF000000ll);
  const __m128i six = _mm_or_si128(_mm_and_si128(w, low3), _mm_and_si128(_mm_srli_epi64(w, 8), next3));
  const __m128i lo_q = _mm_set_epi64x(0, -1);
  return _mm_or_si128(_mm_and_si128(six, lo_q), _mm_srli_si128(_mm_andnot_si128(lo_q, six), 2));
}
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

}  // namespace raycast::simd::sse2
