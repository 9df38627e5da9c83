// AVX-512 F + BW + VL: 16 float lanes in one __m512, masks in k-registers. See README.md.
#pragma once
#include <immintrin.h>

#include <cstdint>

#include "simd/inline.h"

// Beyond the common vocabulary (README.md), for the kernel's #ifdef: store4 and store_first.
#define RAYCAST_HAS_STORE4 1
#define RAYCAST_HAS_MASKED_BYTE_STORE 1

namespace raycast::simd::avx512 {

// How many vfloats the register file holds (two samples a pass from 16).
inline constexpr int vfloats_in_registers = 32;

struct vmask {
  __mmask16 m;
};

struct vfloat {
  static constexpr int size = 16;
  __m512 v;
  vfloat() = default;
  RAYCAST_INLINE vfloat(__m512 x) : v(x) {}
  RAYCAST_INLINE vfloat(float s) : v(_mm512_set1_ps(s)) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return _mm512_loadu_ps(p); }
};

struct vint {
  __m512i v;
};

RAYCAST_INLINE vfloat operator+(vfloat a, vfloat b) { return _mm512_add_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator-(vfloat a, vfloat b) { return _mm512_sub_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator*(vfloat a, vfloat b) { return _mm512_mul_ps(a.v, b.v); }
RAYCAST_INLINE vfloat operator/(vfloat a, vfloat b) { return _mm512_div_ps(a.v, b.v); }
// An integer xor: the float one needs AVX-512 DQ.
RAYCAST_INLINE vfloat operator-(vfloat a) {
  return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a.v), _mm512_set1_epi32(INT32_MIN)));
}
RAYCAST_INLINE void store(float* p, vfloat a) { _mm512_storeu_ps(p, a.v); }
RAYCAST_INLINE vmask operator==(vfloat a, vfloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)}; }
RAYCAST_INLINE vfloat min(vfloat a, vfloat b) { return _mm512_min_ps(a.v, b.v); }
RAYCAST_INLINE vfloat max(vfloat a, vfloat b) { return _mm512_max_ps(a.v, b.v); }
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
RAYCAST_INLINE vmask operator>=(vfloat a, vfloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
RAYCAST_INLINE vmask operator<=(vfloat a, vfloat b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
RAYCAST_INLINE vmask operator&(vmask a, vmask b) { return {__mmask16(a.m & b.m)}; }
RAYCAST_INLINE vmask operator|(vmask a, vmask b) { return {__mmask16(a.m | b.m)}; }
RAYCAST_INLINE bool any(vmask m) { return m.m != 0; }
RAYCAST_INLINE bool none(vmask m) { return m.m == 0; }
RAYCAST_INLINE bool all(vmask m) { return m.m == 0xffff; }
RAYCAST_INLINE vmask operator!(vmask m) { return {__mmask16(~m.m)}; }
// A bit select by the sign mask (ternary logic 0xCA: "A ? B : C"; the float and/or need AVX-512 DQ).
RAYCAST_INLINE vfloat copysign(vfloat a, vfloat b) {
  return _mm512_castsi512_ps(_mm512_ternarylogic_epi32(_mm512_set1_epi32(INT32_MIN), _mm512_castps_si512(b.v),
                                                       _mm512_castps_si512(a.v), 0xCA));
}
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) { return _mm512_mask_blend_ps(m.m, b.v, a.v); }
RAYCAST_INLINE vfloat sqrt(vfloat a) { return _mm512_sqrt_ps(a.v); }
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) { return _mm512_fmadd_ps(a.v, b.v, c.v); }
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) { return _mm512_fnmadd_ps(a.v, b.v, c.v); }  // c - a b
// 1/sqrt(x), hardware estimate: relative error below 2^-14.
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) { return _mm512_rsqrt14_ps(x.v); }
RAYCAST_INLINE vint to_int(vfloat a) { return {_mm512_cvttps_epi32(a.v)}; }
RAYCAST_INLINE __m512i reverse_index() {
  return _mm512_setr_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
}
RAYCAST_INLINE vfloat reverse(vfloat a) { return _mm512_permutexvar_ps(reverse_index(), a.v); }
RAYCAST_INLINE vint reverse(vint a) { return {_mm512_permutexvar_epi32(reverse_index(), a.v)}; }
RAYCAST_INLINE vint splat_int(int32_t x) { return {_mm512_set1_epi32(x)}; }

// 16 pixels of RGB8, interleaved in a register: 48 bytes in dwords 0-11.
struct rgb8_pack {
  __m512i v;
};

// (r g b 0) dwords squeezed per 128-bit lane, the twelve useful ones gathered.
template <bool Reversed = false>
RAYCAST_INLINE rgb8_pack pack_rgb8(vint r, vint g, vint b) {
  const __m512i w = _mm512_or_si512(
      r.v, _mm512_or_si512(_mm512_slli_epi32(g.v, 8), _mm512_slli_epi32(b.v, 16)));
  if constexpr (Reversed) {
    const __m512i pack = _mm512_broadcast_i32x4(
        _mm_setr_epi8(12, 13, 14, 8, 9, 10, 4, 5, 6, 0, 1, 2, -1, -1, -1, -1));
    return {_mm512_permutexvar_epi32(
        _mm512_setr_epi32(12, 13, 14, 8, 9, 10, 4, 5, 6, 0, 1, 2, 15, 15, 15, 15),
        _mm512_shuffle_epi8(w, pack))};
  } else {
    const __m512i pack = _mm512_broadcast_i32x4(
        _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1));
    return {_mm512_permutexvar_epi32(
        _mm512_setr_epi32(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 15, 15, 15, 15),
        _mm512_shuffle_epi8(w, pack))};
  }
}
RAYCAST_INLINE void store(unsigned char* dst, rgb8_pack p) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), _mm512_castsi512_si256(p.v));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + 32), _mm512_extracti32x4_epi32(p.v, 2));
}
// The first n < 16 pixels only: a byte-masked store, nothing past 3n bytes touched.
RAYCAST_INLINE void store_first(unsigned char* dst, rgb8_pack p, int n) {
  _mm512_mask_storeu_epi8(dst, (__mmask64{1} << (3 * n)) - 1, p.v);
}
// Four packs side by side (192 bytes) as three full 64-byte stores.
RAYCAST_INLINE void store4(unsigned char* dst, rgb8_pack a, rgb8_pack b, rgb8_pack c, rgb8_pack d) {
  const __m512i lo = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19);
  const __m512i mid = _mm512_setr_epi32(4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 20, 21, 22, 23);
  const __m512i hi = _mm512_setr_epi32(8, 9, 10, 11, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27);
  _mm512_storeu_si512(dst, _mm512_permutex2var_epi32(a.v, lo, b.v));
  _mm512_storeu_si512(dst + 64, _mm512_permutex2var_epi32(b.v, mid, c.v));
  _mm512_storeu_si512(dst + 128, _mm512_permutex2var_epi32(c.v, hi, d.v));
}

// Writes 48 floats r0 g0 b0 r1 ...: the in-lane triple shuffles, then the 128-bit lanes in order.
RAYCAST_INLINE void store_rgbf(float* dst, vfloat r, vfloat g, vfloat b) {
  const __m512 a = _mm512_unpacklo_ps(r.v, g.v);
  const __m512 c = _mm512_shuffle_ps(b.v, r.v, _MM_SHUFFLE(1, 1, 0, 0));
  const __m512 o0 = _mm512_shuffle_ps(a, c, _MM_SHUFFLE(2, 0, 1, 0));
  const __m512 d = _mm512_shuffle_ps(g.v, b.v, _MM_SHUFFLE(1, 1, 1, 1));
  const __m512 e = _mm512_shuffle_ps(r.v, g.v, _MM_SHUFFLE(2, 2, 2, 2));
  const __m512 o1 = _mm512_shuffle_ps(d, e, _MM_SHUFFLE(2, 0, 2, 0));
  const __m512 f = _mm512_shuffle_ps(b.v, r.v, _MM_SHUFFLE(3, 3, 2, 2));
  const __m512 h = _mm512_shuffle_ps(g.v, b.v, _MM_SHUFFLE(3, 3, 3, 3));
  const __m512 o2 = _mm512_shuffle_ps(f, h, _MM_SHUFFLE(2, 0, 2, 0));
  // oK holds part K of pixel quads A, B, C, D in its 128-bit lanes. Output: [o0.A o1.A o2.A o0.B]
  // [o1.B o2.B o0.C o1.C] [o2.C o0.D o1.D o2.D], each a two-source and a masked permute.
  const auto idx = [](int l0, int l1, int l2, int l3) {  // 128-bit lanes; 4..7: second source
    return _mm512_setr_epi32(4 * l0, 4 * l0 + 1, 4 * l0 + 2, 4 * l0 + 3, 4 * l1, 4 * l1 + 1,
                             4 * l1 + 2, 4 * l1 + 3, 4 * l2, 4 * l2 + 1, 4 * l2 + 2, 4 * l2 + 3,
                             4 * l3, 4 * l3 + 1, 4 * l3 + 2, 4 * l3 + 3);
  };
  __m512 out0 = _mm512_permutex2var_ps(o0, idx(0, 4, 0, 1), o1);
  out0 = _mm512_mask_permutexvar_ps(out0, 0x0F00, idx(0, 0, 0, 0), o2);
  __m512 out1 = _mm512_permutex2var_ps(o1, idx(1, 1, 6, 2), o0);
  out1 = _mm512_mask_permutexvar_ps(out1, 0x00F0, idx(1, 1, 1, 1), o2);
  __m512 out2 = _mm512_permutex2var_ps(o2, idx(2, 7, 2, 3), o0);
  out2 = _mm512_mask_permutexvar_ps(out2, 0x0F00, idx(3, 3, 3, 3), o1);
  _mm512_storeu_ps(dst + 0, out0);
  _mm512_storeu_ps(dst + 16, out1);
  _mm512_storeu_ps(dst + 32, out2);
}

struct vuint {
  __m512i v;
  vuint() = default;
  RAYCAST_INLINE vuint(__m512i x) : v(x) {}
  explicit RAYCAST_INLINE vuint(uint32_t s) : v(_mm512_set1_epi32(int32_t(s))) {}
  static RAYCAST_INLINE vuint iota(uint32_t start) {
    return _mm512_add_epi32(_mm512_set1_epi32(int32_t(start)),
                            _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
  }
};
RAYCAST_INLINE vuint operator+(vuint a, vuint b) { return _mm512_add_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator-(vuint a, vuint b) { return _mm512_sub_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator*(vuint a, vuint b) { return _mm512_mullo_epi32(a.v, b.v); }
RAYCAST_INLINE vuint operator^(vuint a, vuint b) { return _mm512_xor_si512(a.v, b.v); }
RAYCAST_INLINE vuint operator&(vuint a, vuint b) { return _mm512_and_si512(a.v, b.v); }
RAYCAST_INLINE vuint operator|(vuint a, vuint b) { return _mm512_or_si512(a.v, b.v); }
RAYCAST_INLINE vuint operator>>(vuint a, int n) { return _mm512_srli_epi32(a.v, unsigned(n)); }
RAYCAST_INLINE vuint operator<<(vuint a, int n) { return _mm512_slli_epi32(a.v, unsigned(n)); }
RAYCAST_INLINE vfloat to_float(vuint a) { return _mm512_cvtepi32_ps(a.v); }
RAYCAST_INLINE vuint as_uint(vfloat a) { return _mm512_castps_si512(a.v); }
RAYCAST_INLINE vfloat as_float(vuint a) { return _mm512_castsi512_ps(a.v); }
RAYCAST_INLINE vmask operator>(vuint a, vuint b) { return {_mm512_cmpgt_epu32_mask(a.v, b.v)}; }
RAYCAST_INLINE vuint select(vmask m, vuint a, vuint b) { return _mm512_mask_blend_epi32(m.m, b.v, a.v); }

}  // namespace raycast::simd::avx512
