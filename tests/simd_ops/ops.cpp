// ops.h's table for one target, compiled once per target of simd/targets.h
// with its flags (tests/CMakeLists.txt: RAYCAST_ISA is its name,
// RAYCAST_TARGET_HEADER its vector layer, included first). Intrinsics and
// arrays only.
#include RAYCAST_TARGET_HEADER

#include "ops.h"

namespace raycast_test::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;

void load_store(const float* in, float* out) { store(out, vfloat::load(in)); }
void reverse_lanes(const float* in, float* out) { store(out, reverse(vfloat::load(in))); }
void half_plus_and_negate(const float* in, float* half_plus, float* negated) {
  const vfloat x = vfloat::load(in);
  store(half_plus, (x + 1.0f) * 0.5f);
  store(negated, -x);
}
void select_zero(const float* key, const float* a, float b, float* out) {
  store(out, select(vfloat::load(key) == 0.0f, vfloat::load(a), b));
}
void pack(const float* r, const float* g, const float* b, bool reversed, unsigned char* out) {
  const vint ri = to_int(vfloat::load(r)), gi = to_int(vfloat::load(g)), bi = to_int(vfloat::load(b));
  store(out, reversed ? pack_rgb8<true>(ri, gi, bi) : pack_rgb8<false>(ri, gi, bi));
}
void reverse_ints_then_pack(const float* r, const float* g, const float* b, unsigned char* out) {
  store(out, pack_rgb8<false>(reverse(to_int(vfloat::load(r))), reverse(to_int(vfloat::load(g))),
                              reverse(to_int(vfloat::load(b)))));
}
void store_interleaved(const float* r, const float* g, const float* b, float* out) {
  store_rgbf(out, vfloat::load(r), vfloat::load(g), vfloat::load(b));
}
#ifdef RAYCAST_HAS_STORE4
void store_four(const float* rgb, unsigned char* out) {
  rgb8_pack p[4];
  for (int k = 0; k < 4; ++k) {
    const float* c = rgb + 3 * N * k;
    p[k] = pack_rgb8<false>(to_int(vfloat::load(c)), to_int(vfloat::load(c + N)),
                            to_int(vfloat::load(c + 2 * N)));
  }
  store4(out, p[0], p[1], p[2], p[3]);
}
#endif
#ifdef RAYCAST_HAS_MASKED_BYTE_STORE
void store_first_pixels(const float* r, const float* g, const float* b, int n, unsigned char* out) {
  store_first(out, pack_rgb8<false>(to_int(vfloat::load(r)), to_int(vfloat::load(g)), to_int(vfloat::load(b))), n);
}
#endif

void compare(const float* a, const float* b, float* ge, float* le, float* both, float* either,
             bool* any_ge, bool* none_ge, bool* all_ge, float* not_ge, float* empty) {
  const vfloat x = vfloat::load(a), y = vfloat::load(b);
  const vmask g = x >= y, l = x <= y;
  store(ge, select(g, 1.0f, 0.0f));
  store(le, select(l, 1.0f, 0.0f));
  store(both, select(g & l, 1.0f, 0.0f));
  store(either, select(g | l, 1.0f, 0.0f));
  *any_ge = any(g);
  *none_ge = none(g);
  *all_ge = all(g);
  store(not_ge, select(!g, 1.0f, 0.0f));
  store(empty, select(vmask{}, 1.0f, 0.0f));
}
void copy_sign(const float* mag, const float* sign, float* out) {
  store(out, copysign(vfloat::load(mag), vfloat::load(sign)));
}
void select_equal(const float* x, const float* y, const float* a, const float* b, float* out) {
  store(out, select(vfloat::load(x) == vfloat::load(y), vfloat::load(a), vfloat::load(b)));
}
void min_max(const float* a, const float* b, float lo, float hi, float* mx, float* mn, float* clamped) {
  const vfloat x = vfloat::load(a), y = vfloat::load(b);
  store(mx, max(x, y));
  store(mn, min(x, y));
  store(clamped, clamp(x, lo, hi));
}
void arithmetic(const float* a, const float* b, const float* c, float* mul_add, float* div_sqrt) {
  const vfloat x = vfloat::load(a), y = vfloat::load(b);
  store(mul_add, x * y + vfloat::load(c));
  store(div_sqrt, x / sqrt(y));
}
void rsqrt_estimate(const float* in, float* out) { store(out, rsqrt_est(vfloat::load(in))); }

// The integer vectors' lanes, in and out by their bytes (lane 0 first in
// memory on every instruction set here).
static_assert(sizeof(vint) == 4 * N && sizeof(vuint) == 4 * N);
vint ints(const int32_t* p) {
  vint v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
void put(int32_t* p, vint v) { __builtin_memcpy(p, &v, sizeof v); }
vuint uints(const uint32_t* p) {
  vuint v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
void put(uint32_t* p, vuint v) { __builtin_memcpy(p, &v, sizeof v); }

void splat(int32_t x, int32_t* out) { put(out, splat_int(x)); }
void truncate(const float* in, int32_t* out) { put(out, to_int(vfloat::load(in))); }
void reverse_ints(const int32_t* in, int32_t* out) { put(out, reverse(ints(in))); }
void uint_splat_iota(uint32_t s, uint32_t* splat, uint32_t* iota) {
  put(splat, vuint(s));
  put(iota, vuint::iota(s));
}
void uint_arithmetic(const uint32_t* a, const uint32_t* b, uint32_t* add, uint32_t* sub, uint32_t* mul,
                     uint32_t* bit_xor, uint32_t* bit_and, uint32_t* bit_or) {
  const vuint x = uints(a), y = uints(b);
  put(add, x + y);
  put(sub, x - y);
  put(mul, x * y);
  put(bit_xor, x ^ y);
  put(bit_and, x & y);
  put(bit_or, x | y);
}
void uint_shift(const uint32_t* a, int n, uint32_t* shr, uint32_t* shl) {
  const vuint x = uints(a);
  put(shr, x >> n);
  put(shl, x << n);
}
template <int K>
void shift_by_constants(vuint x, uint32_t* shr, uint32_t* shl) {
  if constexpr (K < 32) {
    put(shr + K * N, x >> K);
    put(shl + K * N, x << K);
    shift_by_constants<K + 1>(x, shr, shl);
  }
}
void uint_shift_constants(const uint32_t* a, uint32_t* shr, uint32_t* shl) {
  shift_by_constants<0>(uints(a), shr, shl);
}
void uint_to_float(const uint32_t* in, float* out) { store(out, to_float(uints(in))); }
void float_bits(const float* in, uint32_t* bits, float* back) {
  const vuint u = as_uint(vfloat::load(in));
  put(bits, u);
  store(back, as_float(u));
}

void uint_compare_select(const uint32_t* a, const uint32_t* b, uint32_t* greater, uint32_t* larger) {
  const vuint x = uints(a), y = uints(b);
  const vmask m = x > y;
  put(greater, select(m, vuint(1u), vuint(0u)));
  put(larger, select(m, x, y));
}

}  // namespace

extern const simd_ops ops = {
    N, load_store, reverse_lanes, half_plus_and_negate, select_zero, pack, reverse_ints_then_pack,
    store_interleaved,
#ifdef RAYCAST_HAS_STORE4
    store_four,
#else
    nullptr,
#endif
#ifdef RAYCAST_HAS_MASKED_BYTE_STORE
    store_first_pixels,
#else
    nullptr,
#endif
    compare, copy_sign, select_equal, min_max, arithmetic, rsqrt_estimate,
    splat, truncate, reverse_ints, uint_splat_iota, uint_arithmetic, uint_shift, uint_shift_constants,
    uint_to_float, float_bits, uint_compare_select,
};

}  // namespace raycast_test::RAYCAST_ISA
