// NEON (every AArch64): 8 float lanes as two float32x4_t halves, the shape of
// the SSE2 header (sse2.h), so the kernel's batch and mirroring logic is the
// one x86 runs. See README.md.
//
// Exact mode depends on every operation here rounding once, as the scalar
// renderer does: + - * / and sqrt are IEEE (vaddq, vsubq, vmulq, vdivq,
// vsqrtq), and nothing is fused. The kernel is compiled with -ffp-contract=off
// so the compiler does not fuse a vmulq and a vaddq into an fmla behind our
// back; vfmaq appears only in madd / nmadd, which only fast mode uses.
#pragma once
#include <arm_neon.h>

#include <cstdint>

#include "simd/inline.h"

namespace raycast::simd::neon {

// What this instruction set offers beyond the common vocabulary (README.md):
// none. The kernel falls back to plain stores.

// How many vfloats the register file holds (32 q registers, two per vfloat): the sphere kernel's
// sampled path takes two samples a pass where that is 16 or more.
inline constexpr int vfloats_in_registers = 16;

struct vmask {
  uint32x4_t lo, hi;
};

struct vfloat {
  static constexpr int size = 8;
  float32x4_t lo, hi;
  vfloat() = default;
  RAYCAST_INLINE vfloat(float32x4_t l, float32x4_t h) : lo(l), hi(h) {}
  // Every lane s; implicit, as Embree's, so that kernels write (uy + 1.0f) * 0.5f.
  RAYCAST_INLINE vfloat(float s) : lo(vdupq_n_f32(s)), hi(lo) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return {vld1q_f32(p), vld1q_f32(p + 4)}; }
};

struct vint {
  int32x4_t lo, hi;
};

#define RAYCAST_NEON_BINARY(name, op) \
  RAYCAST_INLINE vfloat name(vfloat a, vfloat b) { return {op(a.lo, b.lo), op(a.hi, b.hi)}; }
RAYCAST_NEON_BINARY(operator+, vaddq_f32)
RAYCAST_NEON_BINARY(operator-, vsubq_f32)
RAYCAST_NEON_BINARY(operator*, vmulq_f32)
RAYCAST_NEON_BINARY(operator/, vdivq_f32)
#undef RAYCAST_NEON_BINARY

// IEEE negation (the sign bit flipped), as the scalar -x: -(+0) is -0.
RAYCAST_INLINE vfloat operator-(vfloat a) { return {vnegq_f32(a.lo), vnegq_f32(a.hi)}; }
RAYCAST_INLINE void store(float* p, vfloat a) {
  vst1q_f32(p, a.lo);
  vst1q_f32(p + 4, a.hi);
}

// min and max with the x86 (and scalar.cpp) meaning, a > b ? a : b: NEON's
// fmax returns NaN for a NaN operand and +0 for max(+0, -0), where maxps (and
// the scalar renderer) return the second operand. A compare and a bit select
// keep every backend's bits the same, signed zeros and NaNs included.
RAYCAST_INLINE vfloat max(vfloat a, vfloat b) {
  return {vbslq_f32(vcgtq_f32(a.lo, b.lo), a.lo, b.lo), vbslq_f32(vcgtq_f32(a.hi, b.hi), a.hi, b.hi)};
}
RAYCAST_INLINE vfloat min(vfloat a, vfloat b) {
  return {vbslq_f32(vcltq_f32(a.lo, b.lo), a.lo, b.lo), vbslq_f32(vcltq_f32(a.hi, b.hi), a.hi, b.hi)};
}

RAYCAST_INLINE vmask operator==(vfloat a, vfloat b) { return {vceqq_f32(a.lo, b.lo), vceqq_f32(a.hi, b.hi)}; }
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
// Ordered comparisons (false where either lane is NaN); vmask{} is all false.
RAYCAST_INLINE vmask operator>=(vfloat a, vfloat b) { return {vcgeq_f32(a.lo, b.lo), vcgeq_f32(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator<=(vfloat a, vfloat b) { return {vcleq_f32(a.lo, b.lo), vcleq_f32(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator&(vmask a, vmask b) { return {vandq_u32(a.lo, b.lo), vandq_u32(a.hi, b.hi)}; }
RAYCAST_INLINE vmask operator|(vmask a, vmask b) { return {vorrq_u32(a.lo, b.lo), vorrq_u32(a.hi, b.hi)}; }
RAYCAST_INLINE bool any(vmask m) { return vmaxvq_u32(vorrq_u32(m.lo, m.hi)) != 0; }
RAYCAST_INLINE bool none(vmask m) { return !any(m); }
RAYCAST_INLINE bool all(vmask m) { return vminvq_u32(vandq_u32(m.lo, m.hi)) != 0; }
RAYCAST_INLINE vmask operator!(vmask m) { return {vmvnq_u32(m.lo), vmvnq_u32(m.hi)}; }
// |a| with the sign of b, as std::copysign: a bit select by the sign bit.
RAYCAST_INLINE vfloat copysign(vfloat a, vfloat b) {
  const uint32x4_t sign = vdupq_n_u32(0x80000000u);
  return {vbslq_f32(sign, b.lo, a.lo), vbslq_f32(sign, b.hi, a.hi)};
}
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) {  // m ? a : b
  return {vbslq_f32(m.lo, a.lo, b.lo), vbslq_f32(m.hi, a.hi, b.hi)};
}
RAYCAST_INLINE vfloat sqrt(vfloat a) { return {vsqrtq_f32(a.lo), vsqrtq_f32(a.hi)}; }
// Fused, one rounding (fast mode only, as on AVX2).
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) {  // a b + c
  return {vfmaq_f32(c.lo, a.lo, b.lo), vfmaq_f32(c.hi, a.hi, b.hi)};
}
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) {  // c - a b
  return {vfmsq_f32(c.lo, a.lo, b.lo), vfmsq_f32(c.hi, a.hi, b.hi)};
}
// 1/sqrt(x). FRSQRTE alone gives about 8 bits (relative error up to 3.3e-3,
// 2^-8.25, measured over [1, 4) under qemu), too coarse for the kernel's single
// Newton step: it would leave ~1.5 e^2 = 1.6e-5, beyond fast mode's 3e-6 bound.
// One FRSQRTS step here, r (3 - x r r) / 2, brings it to 1.6e-5 (2^-15.9),
// finer than x86's rsqrtps (1.5 * 2^-12); the kernel's biased Newton step then
// does the rest, as on x86.
RAYCAST_INLINE float32x4_t rsqrt_est_half(float32x4_t x) {
  const float32x4_t r = vrsqrteq_f32(x);
  return vmulq_f32(r, vrsqrtsq_f32(vmulq_f32(x, r), r));
}
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) { return {rsqrt_est_half(x.lo), rsqrt_est_half(x.hi)}; }
// Truncating, as cvttps2dq (the kernel only converts values in range).
RAYCAST_INLINE vint to_int(vfloat a) { return {vcvtq_s32_f32(a.lo), vcvtq_s32_f32(a.hi)}; }
// Lanes in the opposite order (the mirrored pixels of a batch): each half
// reversed, and the halves swapped.
RAYCAST_INLINE float32x4_t reverse_half(float32x4_t a) {
  const float32x4_t r = vrev64q_f32(a);  // 1 0 3 2
  return vextq_f32(r, r, 2);             // 3 2 1 0
}
RAYCAST_INLINE int32x4_t reverse_half(int32x4_t a) {
  const int32x4_t r = vrev64q_s32(a);
  return vextq_s32(r, r, 2);
}
RAYCAST_INLINE vfloat reverse(vfloat a) { return {reverse_half(a.hi), reverse_half(a.lo)}; }
RAYCAST_INLINE vint reverse(vint a) { return {reverse_half(a.hi), reverse_half(a.lo)}; }
RAYCAST_INLINE vint splat_int(int32_t x) { return {vdupq_n_s32(x), vdupq_n_s32(x)}; }

// 8 pixels of RGB8 as three planes of 8 bytes; store() interleaves them with
// one st3 (NEON's structure store does what SSE2 needs shifts for).
struct rgb8_pack {
  uint8x8x3_t v;
};

// 8 lanes of bytes (0..255 in 32-bit lanes) -> 8 bytes: two narrowing moves.
RAYCAST_INLINE uint8x8_t narrow_bytes(vint x) {
  const uint16x8_t w = vcombine_u16(vmovn_u32(vreinterpretq_u32_s32(x.lo)), vmovn_u32(vreinterpretq_u32_s32(x.hi)));
  return vmovn_u16(w);
}
// Reversed puts the pixels in the opposite order (the mirrored batch).
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

// Unsigned 32-bit lanes for the samplers' counter-based hashes
// (scene/sampler.h): wrap-around + and *, xor, logical shifts (by a
// register count: vshrq_n needs an immediate even where not inlined).
struct vuint {
  uint32x4_t lo, hi;
  vuint() = default;
  RAYCAST_INLINE vuint(uint32x4_t l, uint32x4_t h) : lo(l), hi(h) {}
  RAYCAST_INLINE vuint(uint32_t s) : lo(vdupq_n_u32(s)), hi(lo) {}
  // start, start + 1, ... in lane order.
  static RAYCAST_INLINE vuint iota(uint32_t start) {
    static constexpr uint32_t k[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    const uint32x4_t s = vdupq_n_u32(start);
    return {vaddq_u32(s, vld1q_u32(k)), vaddq_u32(s, vld1q_u32(k + 4))};
  }
};
#define RAYCAST_NEON_UINT(name, op) \
  RAYCAST_INLINE vuint name(vuint a, vuint b) { return {op(a.lo, b.lo), op(a.hi, b.hi)}; }
RAYCAST_NEON_UINT(operator+, vaddq_u32)
RAYCAST_NEON_UINT(operator-, vsubq_u32)
RAYCAST_NEON_UINT(operator*, vmulq_u32)
RAYCAST_NEON_UINT(operator^, veorq_u32)
RAYCAST_NEON_UINT(operator&, vandq_u32)
RAYCAST_NEON_UINT(operator|, vorrq_u32)
#undef RAYCAST_NEON_UINT
RAYCAST_INLINE vuint operator>>(vuint a, int n) {
  const int32x4_t c = vdupq_n_s32(-n);
  return {vshlq_u32(a.lo, c), vshlq_u32(a.hi, c)};
}
RAYCAST_INLINE vuint operator<<(vuint a, int n) {
  const int32x4_t c = vdupq_n_s32(n);
  return {vshlq_u32(a.lo, c), vshlq_u32(a.hi, c)};
}
// Lanes below 2^31, as floats (exact below 2^24).
RAYCAST_INLINE vfloat to_float(vuint a) { return {vcvtq_f32_u32(a.lo), vcvtq_f32_u32(a.hi)}; }

// The bits of a float as an unsigned integer, and back.
RAYCAST_INLINE vuint as_uint(vfloat a) { return {vreinterpretq_u32_f32(a.lo), vreinterpretq_u32_f32(a.hi)}; }
RAYCAST_INLINE vfloat as_float(vuint a) { return {vreinterpretq_f32_u32(a.lo), vreinterpretq_f32_u32(a.hi)}; }

}  // namespace raycast::simd::neon
