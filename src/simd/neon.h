// NEON (every AArch64): 8 float lanes as two float32x4_t halves, as SSE2 (two_halves.inl). See
// README.md. Exact mode needs every operation to round once: + - * / and sqrt are IEEE, and with
// -ffp-contract=off only madd / nmadd (fast mode) fuse.
#pragma once
#include <arm_neon.h>

#include <cstdint>

#include "simd/inline.h"

namespace raycast::simd::neon {

namespace half {
using f = float32x4_t;
using i = int32x4_t;
using u = uint32x4_t;
using m = uint32x4_t;
inline constexpr int registers = 32;  // v0-v31
RAYCAST_INLINE f splat(float s) { return vdupq_n_f32(s); }
RAYCAST_INLINE f load(const float* p) { return vld1q_f32(p); }
RAYCAST_INLINE void store(float* p, f a) { vst1q_f32(p, a); }
RAYCAST_INLINE f add(f a, f b) { return vaddq_f32(a, b); }
RAYCAST_INLINE f sub(f a, f b) { return vsubq_f32(a, b); }
RAYCAST_INLINE f mul(f a, f b) { return vmulq_f32(a, b); }
RAYCAST_INLINE f div(f a, f b) { return vdivq_f32(a, b); }
// min and max with x86's meaning, a > b ? a : b (fmax differs on NaN and signed zeros).
RAYCAST_INLINE f max(f a, f b) { return vbslq_f32(vcgtq_f32(a, b), a, b); }
RAYCAST_INLINE f min(f a, f b) { return vbslq_f32(vcltq_f32(a, b), a, b); }
RAYCAST_INLINE f neg(f a) { return vnegq_f32(a); }
RAYCAST_INLINE f copysign(f a, f b) { return vbslq_f32(vdupq_n_u32(0x80000000u), b, a); }
RAYCAST_INLINE m eq(f a, f b) { return vceqq_f32(a, b); }
RAYCAST_INLINE m ge(f a, f b) { return vcgeq_f32(a, b); }
RAYCAST_INLINE m le(f a, f b) { return vcleq_f32(a, b); }
RAYCAST_INLINE m and_mask(m a, m b) { return vandq_u32(a, b); }
RAYCAST_INLINE m or_mask(m a, m b) { return vorrq_u32(a, b); }
RAYCAST_INLINE m not_mask(m a) { return vmvnq_u32(a); }
RAYCAST_INLINE bool any(m a) { return vmaxvq_u32(a) != 0; }
RAYCAST_INLINE bool all(m a) { return vminvq_u32(a) != 0; }
RAYCAST_INLINE f select(m k, f a, f b) { return vbslq_f32(k, a, b); }
RAYCAST_INLINE f sqrt(f a) { return vsqrtq_f32(a); }
// Fused, one rounding (fast mode only, as on AVX2).
RAYCAST_INLINE f madd(f a, f b, f c) { return vfmaq_f32(c, a, b); }
RAYCAST_INLINE f nmadd(f a, f b, f c) { return vfmsq_f32(c, a, b); }
// 1/sqrt(x): FRSQRTE's 8 bits are too coarse for the kernel's one Newton step (fast mode's 3e-6
// bound); one FRSQRTS step, r (3 - x r r) / 2, brings it to 1.6e-5, finer than x86's estimate.
RAYCAST_INLINE f rsqrt_est(f x) {
  const float32x4_t r = vrsqrteq_f32(x);
  return vmulq_f32(r, vrsqrtsq_f32(vmulq_f32(x, r), r));
}
// Truncating, as cvttps2dq.
RAYCAST_INLINE i to_int(f a) { return vcvtq_s32_f32(a); }
RAYCAST_INLINE f reverse(f a) {
  const float32x4_t r = vrev64q_f32(a);  // 1 0 3 2
  return vextq_f32(r, r, 2);             // 3 2 1 0
}
RAYCAST_INLINE i reverse(i a) {
  const int32x4_t r = vrev64q_s32(a);
  return vextq_s32(r, r, 2);
}
RAYCAST_INLINE i splat_int(int32_t x) { return vdupq_n_s32(x); }
RAYCAST_INLINE u splat_u(uint32_t s) { return vdupq_n_u32(s); }
RAYCAST_INLINE u iota(uint32_t start) {
  static constexpr uint32_t k[4] = {0, 1, 2, 3};
  return vaddq_u32(vdupq_n_u32(start), vld1q_u32(k));
}
RAYCAST_INLINE u add_u(u a, u b) { return vaddq_u32(a, b); }
RAYCAST_INLINE u sub_u(u a, u b) { return vsubq_u32(a, b); }
RAYCAST_INLINE u mul_u(u a, u b) { return vmulq_u32(a, b); }
RAYCAST_INLINE u xor_u(u a, u b) { return veorq_u32(a, b); }
RAYCAST_INLINE u and_u(u a, u b) { return vandq_u32(a, b); }
RAYCAST_INLINE u or_u(u a, u b) { return vorrq_u32(a, b); }
// Shifts by a register count: vshrq_n needs an immediate.
RAYCAST_INLINE u shr(u a, int n) { return vshlq_u32(a, vdupq_n_s32(-n)); }
RAYCAST_INLINE u shl(u a, int n) { return vshlq_u32(a, vdupq_n_s32(n)); }
RAYCAST_INLINE f to_float(u a) { return vcvtq_f32_u32(a); }
RAYCAST_INLINE u as_uint(f a) { return vreinterpretq_u32_f32(a); }
RAYCAST_INLINE f as_float(u a) { return vreinterpretq_f32_u32(a); }
RAYCAST_INLINE m gt_u(u a, u b) { return vcgtq_u32(a, b); }
RAYCAST_INLINE u select_u(m k, u a, u b) { return vbslq_u32(k, a, b); }
}  // namespace half

#include "simd/two_halves.inl"

// 8 pixels of RGB8 as three planes of 8 bytes; store() interleaves them with one st3.
struct rgb8_pack {
  uint8x8x3_t v;
};

// 8 lanes of bytes (0..255 in 32-bit lanes) -> 8 bytes: two narrowing moves.
RAYCAST_INLINE uint8x8_t narrow_bytes(vint x) {
  const uint16x8_t w = vcombine_u16(vmovn_u32(vreinterpretq_u32_s32(x.lo)), vmovn_u32(vreinterpretq_u32_s32(x.hi)));
  return vmovn_u16(w);
}
template <bool Reversed = false>
RAYCAST_INLINE rgb8_pack pack_rgb8(vint r, vint g, vint b) {
  rgb8_pack p;
  p.v.val[0] = narrow_bytes(r);
  p.v.val[1] = narrow_bytes(g);
  p.v.val[2] = narrow_bytes(b);
  if constexpr (Reversed) {
    for (int k = 0; k < 3; ++k) p.v.val[k] = vrev64_u8(p.v.val[k]);
  }
  return p;
}
// Exactly 24 bytes.
RAYCAST_INLINE void store(unsigned char* dst, rgb8_pack p) { vst3_u8(dst, p.v); }

// Writes 24 floats r0 g0 b0 r1 g1 b1 ... (st3, one per half).
RAYCAST_INLINE void store_rgbf(float* dst, vfloat r, vfloat g, vfloat b) {
  vst3q_f32(dst, (float32x4x3_t{{r.lo, g.lo, b.lo}}));
  vst3q_f32(dst + 12, (float32x4x3_t{{r.hi, g.hi, b.hi}}));
}

}  // namespace raycast::simd::neon
