// AVX2 + FMA: 8 float lanes in one __m256. See README.md.
#pragma once
#include <immintrin.h>

#include <cstdint>

#include "simd/inline.h"

namespace raycast::simd::avx2 {

// How many vfloats the register file holds (two samples a pass from 16).
inline constexpr int vfloats_in_registers = 16;

struct vmask {
  __m256 m;
};

struct vfloat {
  static constexpr int size = 8;
  __m256 v;
  vfloat() = default;
  RAYCAST_INLINE vfloat(__m256 x) : v(x) {}
  RAYCAST_INLINE vfloat(float s) : v(_mm256_set1_ps(s)) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return _mm256_loadu_ps(p); }
};

struct vint {
  __m256i v;
};

RAYCAST_INLINE vfloat operator+(vfloat a, vfloat b) { return _mm256_add_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator-(vfloat a, vfloat b) { return _mm256_sub_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator*(vfloat a, vfloat b) { return _mm256_mul_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator/(vfloat a, vfloat b) { return _mm256_div_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator-(vfloat a) { return _mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f)); }
RAYCAST_INLINE void store(float* p, vfloat a) { _mm256_storeu_ps(p, a.v); }
RAYCAST_INLINE vmask operator==(vfloat a, vfloat b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)}; }
RAYCAST_INLINE vfloat min(vfloat a, vfloat b) { return _mm256_min_ps(a.v, b.v); }
RAYCAST_INLINE vfloat max(vfloat a, vfloat b) { return _mm256_max_ps(a.v, b.v); }
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
RAYCAST_INLINE vmask operator>=(vfloat a, vfloat b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
RAYCAST_INLINE vmask operator<=(vfloat a, vfloat b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
RAYCAST_INLINE vmask operator&(vmask a, vmask b) { return {_mm256_and_ps(a.m, b.m)}; }
RAYCAST_INLINE vmask operator|(vmask a, vmask b) { return {_mm256_or_ps(a.m, b.m)}; }
RAYCAST_INLINE bool any(vmask m) { return _mm256_movemask_ps(m.m) != 0; }
RAYCAST_INLINE bool none(vmask m) { return !any(m); }
RAYCAST_INLINE bool all(vmask m) { return _mm256_movemask_ps(m.m) == 0xff; }
RAYCAST_INLINE vmask operator!(vmask m) { return {_mm256_xor_ps(m.m, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))}; }
RAYCAST_INLINE vfloat copysign(vfloat a, vfloat b) {
  const __m256 sign = _mm256_set1_ps(-0.0f);
  return _mm256_or_ps(_mm256_andnot_ps(sign, a.v), _mm256_and_ps(sign, b.v));
}
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) { return _mm256_blendv_ps(b.v, a.v, m.m); }
RAYCAST_INLINE vfloat sqrt(vfloat a) { return _mm256_sqrt_ps(a.v); }
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) { return _mm256_fmadd_ps(a.v, b.v, c.v); }
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) { return _mm256_fnmadd_ps(a.v, b.v, c.v); }  // c - a b
// 1/sqrt(x), hardware estimate: relative error below 1.5 * 2^-12.
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) { return _mm256_rsqrt_ps(x.v); }
RAYCAST_INLINE vint to_int(vfloat a) { return {_mm256_cvttps_epi32(a.v)}; }
RAYCAST_INLINE vfloat reverse(vfloat a) {
  return _mm256_permutevar8x32_ps(a.v, _mm256_setr_epi32(7, 6, 5, 4, 3, 2, 1, 0));
}
RAYCAST_INLINE vint reverse(vint a) {
  return {_mm256_permutevar8x32_epi32(a.v, _mm256_setr_epi32(7, 6, 5, 4, 3, 2, 1, 0))};
}
RAYCAST_INLINE vint splat_int(int32_t x) { return {_mm256_set1_epi32(x)}; }

// 8 pixels of RGB8, interleaved in a register: 24 bytes in dwords 0-5.
struct rgb8_pack {
  __m256i v;
};

// Per 128-bit lane: 4 x (r g b 0) -> 12 packed bytes, then the two lanes' 3 dwords side by side.
template <bool Reversed = false>
RAYCAST_INLINE rgb8_pack pack_rgb8(vint r, vint g, vint b) {
  __m256i w = _mm256_or_si256(
      r.v, _mm256_or_si256(_mm256_slli_epi32(g.v, 8), _mm256_slli_epi32(b.v, 16)));
  if constexpr (Reversed) w = _mm256_permutevar8x32_epi32(w, _mm256_setr_epi32(7, 6, 5, 4, 3, 2, 1, 0));
  const __m256i pack = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,  //
                                        0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
  return {_mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(w, pack),
                                      _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 7, 7))};
}
RAYCAST_INLINE void store(unsigned char* dst, rgb8_pack p) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm256_castsi256_si128(p.v));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(dst + 16), _mm256_extracti128_si256(p.v, 1));
}

// Writes 24 floats r0 g0 b0 r1 g1 b1 ...: within each 128-bit lane, three vectors of triples.
RAYCAST_INLINE void store_rgbf(float* dst, vfloat r, vfloat g, vfloat b) {
  const __m256 a = _mm256_unpacklo_ps(r.v, g.v);                               // r0 g0 r1 g1
  const __m256 c = _mm256_shuffle_ps(b.v, r.v, _MM_SHUFFLE(1, 1, 0, 0));       // b0 b0 r1 r1
  const __m256 o0 = _mm256_shuffle_ps(a, c, _MM_SHUFFLE(2, 0, 1, 0));          // r0 g0 b0 r1
  const __m256 d = _mm256_shuffle_ps(g.v, b.v, _MM_SHUFFLE(1, 1, 1, 1));       // g1 g1 b1 b1
  const __m256 e = _mm256_shuffle_ps(r.v, g.v, _MM_SHUFFLE(2, 2, 2, 2));       // r2 r2 g2 g2
  const __m256 o1 = _mm256_shuffle_ps(d, e, _MM_SHUFFLE(2, 0, 2, 0));          // g1 b1 r2 g2
  const __m256 f = _mm256_shuffle_ps(b.v, r.v, _MM_SHUFFLE(3, 3, 2, 2));       // b2 b2 r3 r3
  const __m256 h = _mm256_shuffle_ps(g.v, b.v, _MM_SHUFFLE(3, 3, 3, 3));       // g3 g3 b3 b3
  const __m256 o2 = _mm256_shuffle_ps(f, h, _MM_SHUFFLE(2, 0, 2, 0));          // b2 r3 g3 b3
  _mm256_storeu_ps(dst + 0, _mm256_permute2f128_ps(o0, o1, 0x20));
  _mm256_storeu_ps(dst + 8, _mm256_permute2f128_ps(o2, o0, 0x30));
  _mm256_storeu_ps(dst + 16, _mm256_permute2f128_ps(o1, o2, 0x31));
}

struct vuint {
  __m256i v;
  vuint() = default;
  RAYCAST_INLINE vuint(__m256i x) : v(x) {}
  explicit RAYCAST_INLINE vuint(uint32_t s) : v(_mm256_set1_epi32(int32_t(s))) {}
  static RAYCAST_INLINE vuint iota(uint32_t start) {
    return _mm256_add_epi32(_mm256_set1_epi32(int32_t(start)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  }
};
RAYCAST_INLINE vuint operator+(vuint a, vuint b) { return _mm256_add_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator-(vuint a, vuint b) { return _mm256_sub_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator*(vuint a, vuint b) { return _mm256_mullo_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator^(vuint a, vuint b) { return _mm256_xor_si256(a.v, b.v); }
RAYCAST_INLINE vuint operator&(vuint a, vuint b) { return _mm256_and_si256(a.v, b.v); }
RAYCAST_INLINE vuint operator|(vuint a, vuint b) { return _mm256_or_si256(a.v, b.v); }
RAYCAST_INLINE vuint operator>>(vuint a, int n) { return _mm256_srli_epi32(a.v, n); }
RAYCAST_INLINE vuint operator<<(vuint a, int n) { return _mm256_slli_epi32(a.v, n); }
RAYCAST_INLINE vfloat to_float(vuint a) { return _mm256_cvtepi32_ps(a.v); }
RAYCAST_INLINE vuint as_uint(vfloat a) { return _mm256_castps_si256(a.v); }
RAYCAST_INLINE vfloat as_float(vuint a) { return _mm256_castsi256_ps(a.v); }
// Unsigned: a signed compare with the top bits flipped.
RAYCAST_INLINE vmask operator>(vuint a, vuint b) {
  const __m256i top = _mm256_set1_epi32(INT32_MIN);
  return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_xor_si256(a.v, top), _mm256_xor_si256(b.v, top)))};
}
RAYCAST_INLINE vuint select(vmask m, vuint a, vuint b) {
  return _mm256_blendv_epi8(b.v, a.v, _mm256_castps_si256(m.m));
}

}  // namespace raycast::simd::avx2
