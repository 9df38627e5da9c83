// The vector layer's lane-moving operations, wrapped as plain functions over
// arrays, one table per instruction set (ops.inl, compiled once per ISA with
// its flags). The tests (test_simd_ops.cpp) are compiled without ISA flags and
// call a table only after checking that this CPU runs it: no gtest or
// standard-library code is ever compiled with an ISA's flags, so no inline
// function built for AVX-512 can be picked by the linker for the others.
#pragma once

namespace raycast_test {

// Arrays hold `lanes` floats per channel; byte outputs 3 * lanes per pack.
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
};

namespace sse2 { extern const simd_ops ops; }
namespace avx2 { extern const simd_ops ops; }
namespace avx512 { extern const simd_ops ops; }
namespace neon { extern const simd_ops ops; }

}  // namespace raycast_test
