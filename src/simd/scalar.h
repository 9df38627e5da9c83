// The 1-lane target: the vector layer's vocabulary over one float (README.md). Plain IEEE float
// operations, one rounding each (builtins: no library function of another target's flags can
// stand in for them; with -ffp-contract=off madd is a multiply and an add, as on SSE2).
#pragma once
#include <cstdint>
#include <cstring>

#include "simd/inline.h"

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raycast::simd::scalar {

// One float a vfloat: the sampled path's two samples a pass fit in any register file.
inline constexpr int vfloats_in_registers = 16;

struct vmask {
  bool m = false;
};

struct vfloat {
  static constexpr int size = 1;
  float v;
  vfloat() = default;
  RAYCAST_INLINE vfloat(float s) : v(s) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return *p; }
};

struct vint {
  int32_t v;
};

RAYCAST_INLINE vfloat operator+(vfloat a, vfloat b) { return a.v + b.v; }
RAYCAST_INLINE vfloat operator-(vfloat a, vfloat b) { return a.v - b.v; }
RAYCAST_INLINE vfloat operator*(vfloat a, vfloat b) { return a.v * b.v; }
RAYCAST_INLINE vfloat operator/(vfloat a, vfloat b) { return a.v / b.v; }
RAYCAST_INLINE vfloat operator-(vfloat a) { return -a.v; }
RAYCAST_INLINE void store(float* p, vfloat a) { *p = a.v; }
// x86's meaning (the second operand unless the first is strictly smaller / larger), as every target.
RAYCAST_INLINE vfloat min(vfloat a, vfloat b) { return a.v < b.v ? a.v : b.v; }
RAYCAST_INLINE vfloat max(vfloat a, vfloat b) { return a.v > b.v ? a.v : b.v; }
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
RAYCAST_INLINE vmask operator==(vfloat a, vfloat b) { return {a.v == b.v}; }
RAYCAST_INLINE vmask operator>=(vfloat a, vfloat b) { return {a.v >= b.v}; }
RAYCAST_INLINE vmask operator<=(vfloat a, vfloat b) { return {a.v <= b.v}; }
RAYCAST_INLINE vmask operator&(vmask a, vmask b) { return {a.m && b.m}; }
RAYCAST_INLINE vmask operator|(vmask a, vmask b) { return {a.m || b.m}; }
RAYCAST_INLINE vmask operator!(vmask a) { return {!a.m}; }
RAYCAST_INLINE bool any(vmask m) { return m.m; }
RAYCAST_INLINE bool none(vmask m) { return !m.m; }
RAYCAST_INLINE bool all(vmask m) { return m.m; }
RAYCAST_INLINE vfloat copysign(vfloat a, vfloat b) { return __builtin_copysignf(a.v, b.v); }
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) { return m.m ? a : b; }
RAYCAST_INLINE vfloat sqrt(vfloat a) { return __builtin_sqrtf(a.v); }
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) { return a * b + c; }
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) { return c - a * b; }
// 1/sqrt(x): SSE's estimate on x86 (as the SSE2 and AVX2 targets), else IEEE.
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) {
#if defined(__SSE__) || defined(__x86_64__)
  return _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x.v)));
#else
  return 1.0f / __builtin_sqrtf(x.v);
#endif
}
RAYCAST_INLINE vint to_int(vfloat a) { return {int32_t(a.v)}; }
RAYCAST_INLINE vfloat reverse(vfloat a) { return a; }
RAYCAST_INLINE vint reverse(vint a) { return a; }
RAYCAST_INLINE vint splat_int(int32_t x) { return {x}; }

// One pixel of RGB8.
struct rgb8_pack {
  unsigned char rgb[3];
};
template <bool Reversed = false>
RAYCAST_INLINE rgb8_pack pack_rgb8(vint r, vint g, vint b) {
  return {{static_cast<unsigned char>(r.v), static_cast<unsigned char>(g.v), static_cast<unsigned char>(b.v)}};
}
RAYCAST_INLINE void store(unsigned char* dst, rgb8_pack p) { std::memcpy(dst, p.rgb, 3); }
RAYCAST_INLINE void store_rgbf(float* dst, vfloat r, vfloat g, vfloat b) {
  dst[0] = r.v;
  dst[1] = g.v;
  dst[2] = b.v;
}

struct vuint {
  uint32_t v;
  vuint() = default;
  explicit RAYCAST_INLINE vuint(uint32_t s) : v(s) {}
  static RAYCAST_INLINE vuint iota(uint32_t start) { return vuint(start); }
};
RAYCAST_INLINE vuint operator+(vuint a, vuint b) { return vuint(a.v + b.v); }
RAYCAST_INLINE vuint operator-(vuint a, vuint b) { return vuint(a.v - b.v); }
RAYCAST_INLINE vuint operator*(vuint a, vuint b) { return vuint(a.v * b.v); }
RAYCAST_INLINE vuint operator^(vuint a, vuint b) { return vuint(a.v ^ b.v); }
RAYCAST_INLINE vuint operator&(vuint a, vuint b) { return vuint(a.v & b.v); }
RAYCAST_INLINE vuint operator|(vuint a, vuint b) { return vuint(a.v | b.v); }
RAYCAST_INLINE vuint operator>>(vuint a, int n) { return vuint(a.v >> n); }
RAYCAST_INLINE vuint operator<<(vuint a, int n) { return vuint(a.v << n); }
RAYCAST_INLINE vfloat to_float(vuint a) { return float(int32_t(a.v)); }
RAYCAST_INLINE vuint as_uint(vfloat a) {
  uint32_t u;
  std::memcpy(&u, &a.v, sizeof u);
  return vuint(u);
}
RAYCAST_INLINE vfloat as_float(vuint a) {
  float x;
  std::memcpy(&x, &a.v, sizeof x);
  return x;
}
RAYCAST_INLINE vmask operator>(vuint a, vuint b) { return {a.v > b.v}; }
RAYCAST_INLINE vuint select(vmask m, vuint a, vuint b) { return m.m ? a : b; }

}  // namespace raycast::simd::scalar
