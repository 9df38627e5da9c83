// The vector layer's lane-moving operations, wrapped as plain functions over
// arrays, one table per instruction set (ops.inl, compiled once per ISA with
// its flags). The tests (test_simd_ops.cpp) are compiled without ISA flags and
// call a table only after checking that this CPU runs it: no gtest or
// standard-library code is ever compiled with an ISA's flags, so no inline
// function built for AVX-512 can be picked by the linker for the others.
#pragma once
#include <cstdint>

#include "simd/targets.h"

namespace raycast_test {

// Arrays hold `lanes` floats (or 32-bit integers) per channel; byte outputs
// 3 * lanes per pack.
struct simd_ops {
  int lanes;
  void (*load_store)(const float* in, float* out);
  void (*reverse)(const float* in, float* out);
  // (x + 1.0f) * 0.5f with scalar operands, and -x.
  void (*half_plus_and_negate)(const float* in, float* half_plus, float* negated);
  // select(key == 0.0f, a, b).
  void (*select_zero)(const float* key, const float* a, float b, float* out);
  // to_int of r, g and b, packed (optionally reversed) and stored.
  void (*pack)(const float* r, const float* g, const float* b, bool reversed, unsigned char* out);
  // reverse() of each to_int'ed channel, then the plain pack.
  void (*reverse_ints_then_pack)(const float* r, const float* g, const float* b, unsigned char* out);
  void (*store_rgbf)(const float* r, const float* g, const float* b, float* out);
  // Four packs (rgb[batch][channel][lane]) stored with store4; null where the
  // instruction set has none (RAYCAST_HAS_STORE4).
  void (*store4)(const float* rgb, unsigned char* out);
  // The first n pixels of a pack with store_first; null where the instruction
  // set has none (RAYCAST_HAS_MASKED_BYTE_STORE).
  void (*store_first)(const float* r, const float* g, const float* b, int n, unsigned char* out);
  // 1 or 0 per lane for a >= b, a <= b, both (&) and either (|); any, none
  // and all of a >= b; !(a >= b) as 1 or 0; and vmask{} (all false) as 1 or 0.
  void (*compare)(const float* a, const float* b, float* ge, float* le, float* both, float* either,
                  bool* any_ge, bool* none_ge, bool* all_ge, float* not_ge, float* empty);
  // copysign(mag, sign).
  void (*copy_sign)(const float* mag, const float* sign, float* out);
  // select(x == y, a, b), every operand a vector.
  void (*select_equal)(const float* x, const float* y, const float* a, const float* b, float* out);
  // max(a, b), min(a, b) and clamp(a, lo, hi) with scalar bounds.
  void (*min_max)(const float* a, const float* b, float lo, float hi, float* mx, float* mn, float* clamped);
  // a * b + c (two roundings: nothing fused) and a / sqrt(b).
  void (*arithmetic)(const float* a, const float* b, const float* c, float* mul_add, float* div_sqrt);
  void (*rsqrt_est)(const float* in, float* out);

  // vint (no load or store of its own: lanes move in and out by their bytes).
  void (*splat_int)(int32_t x, int32_t* out);
  void (*to_int)(const float* in, int32_t* out);
  void (*reverse_ints)(const int32_t* in, int32_t* out);
  // vuint: vuint(s) and vuint::iota(s).
  void (*uint_splat_iota)(uint32_t s, uint32_t* splat, uint32_t* iota);
  // + - * ^ & | (wrapping).
  void (*uint_arithmetic)(const uint32_t* a, const uint32_t* b, uint32_t* add, uint32_t* sub, uint32_t* mul,
                          uint32_t* bit_xor, uint32_t* bit_and, uint32_t* bit_or);
  // a >> n and a << n, n known only at run time.
  void (*uint_shift)(const uint32_t* a, int n, uint32_t* shr, uint32_t* shl);
  // a >> k and a << k for k = 0 ... 31, each a compile-time count (as the
  // samplers shift), at shr + k * lanes and shl + k * lanes.
  void (*uint_shift_constants)(const uint32_t* a, uint32_t* shr, uint32_t* shl);
  void (*uint_to_float)(const uint32_t* in, float* out);
  // as_uint(x), and as_float(as_uint(x)).
  void (*float_bits)(const float* in, uint32_t* bits, float* back);
  // a > b (unsigned) as 1 or 0, and select(a > b, a, b).
  void (*uint_compare_select)(const uint32_t* a, const uint32_t* b, uint32_t* greater, uint32_t* larger);
};

#define RAYCAST_OPS_TABLE(name, arch, lanes, needs, flags) \
  namespace name {                                          \
  extern const simd_ops ops;                                \
  }
RAYCAST_TARGETS(RAYCAST_OPS_TABLE)
#undef RAYCAST_OPS_TABLE

}  // namespace raycast_test
