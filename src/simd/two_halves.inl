// The vector layer's vocabulary as two 4-lane halves, lo (lanes 0-3) then hi (4-7), for SSE2 and
// NEON: included inside the target's namespace after its `half` namespace (the 4-lane types f, i,
// u, m and their operations). No include guard: each target's namespace gets its own copy.

// How many vfloats the register file holds, two registers a vfloat.
inline constexpr int vfloats_in_registers = half::registers / 2;

struct vmask {
  half::m lo, hi;
};

struct vfloat {
  static constexpr int size = 8;
  half::f lo, hi;
  vfloat() = default;
  RAYCAST_INLINE vfloat(half::f l, half::f h) : lo(l), hi(h) {}
  RAYCAST_INLINE vfloat(float s) : lo(half::splat(s)), hi(lo) {}
  static RAYCAST_INLINE vfloat load(const float* p) { return {half::load(p), half::load(p + 4)}; }
};

struct vint {
  half::i lo, hi;
};

// Unsigned 32-bit lanes for the samplers' hashes: wrap-around + and *, xor, logical shifts.
struct vuint {
  half::u lo, hi;
  vuint() = default;
  RAYCAST_INLINE vuint(half::u l, half::u h) : lo(l), hi(h) {}
  explicit RAYCAST_INLINE vuint(uint32_t s) : lo(half::splat_u(s)), hi(lo) {}
  static RAYCAST_INLINE vuint iota(uint32_t start) { return {half::iota(start), half::iota(start + 4)}; }
};

#define RAYCAST_BY_HALVES(result, name, type, op) \
  RAYCAST_INLINE result name(type a, type b) { return {half::op(a.lo, b.lo), half::op(a.hi, b.hi)}; }
RAYCAST_BY_HALVES(vfloat, operator+, vfloat, add)
RAYCAST_BY_HALVES(vfloat, operator-, vfloat, sub)
RAYCAST_BY_HALVES(vfloat, operator*, vfloat, mul)
RAYCAST_BY_HALVES(vfloat, operator/, vfloat, div)
RAYCAST_BY_HALVES(vfloat, min, vfloat, min)
RAYCAST_BY_HALVES(vfloat, max, vfloat, max)
RAYCAST_BY_HALVES(vfloat, copysign, vfloat, copysign)  // |a| with the sign of b, as std::copysign
// Ordered comparisons (false where either lane is NaN); vmask{} is all false.
RAYCAST_BY_HALVES(vmask, operator==, vfloat, eq)
RAYCAST_BY_HALVES(vmask, operator>=, vfloat, ge)
RAYCAST_BY_HALVES(vmask, operator<=, vfloat, le)
RAYCAST_BY_HALVES(vmask, operator&, vmask, and_mask)
RAYCAST_BY_HALVES(vmask, operator|, vmask, or_mask)
RAYCAST_BY_HALVES(vuint, operator+, vuint, add_u)
RAYCAST_BY_HALVES(vuint, operator-, vuint, sub_u)
RAYCAST_BY_HALVES(vuint, operator*, vuint, mul_u)
RAYCAST_BY_HALVES(vuint, operator^, vuint, xor_u)
RAYCAST_BY_HALVES(vuint, operator&, vuint, and_u)
RAYCAST_BY_HALVES(vuint, operator|, vuint, or_u)
#undef RAYCAST_BY_HALVES

RAYCAST_INLINE vfloat operator-(vfloat a) { return {half::neg(a.lo), half::neg(a.hi)}; }
RAYCAST_INLINE void store(float* p, vfloat a) {
  half::store(p, a.lo);
  half::store(p + 4, a.hi);
}
RAYCAST_INLINE vfloat clamp(vfloat x, vfloat lo, vfloat hi) { return min(max(x, lo), hi); }
RAYCAST_INLINE vmask operator!(vmask m) { return {half::not_mask(m.lo), half::not_mask(m.hi)}; }
RAYCAST_INLINE bool any(vmask m) { return half::any(half::or_mask(m.lo, m.hi)); }
RAYCAST_INLINE bool none(vmask m) { return !any(m); }
RAYCAST_INLINE bool all(vmask m) { return half::all(half::and_mask(m.lo, m.hi)); }
RAYCAST_INLINE vfloat select(vmask m, vfloat a, vfloat b) {  // m ? a : b
  return {half::select(m.lo, a.lo, b.lo), half::select(m.hi, a.hi, b.hi)};
}
RAYCAST_INLINE vfloat sqrt(vfloat a) { return {half::sqrt(a.lo), half::sqrt(a.hi)}; }
RAYCAST_INLINE vfloat madd(vfloat a, vfloat b, vfloat c) {  // a b + c (fused where the target fuses)
  return {half::madd(a.lo, b.lo, c.lo), half::madd(a.hi, b.hi, c.hi)};
}
RAYCAST_INLINE vfloat nmadd(vfloat a, vfloat b, vfloat c) {  // c - a b
  return {half::nmadd(a.lo, b.lo, c.lo), half::nmadd(a.hi, b.hi, c.hi)};
}
RAYCAST_INLINE vfloat rsqrt_est(vfloat x) { return {half::rsqrt_est(x.lo), half::rsqrt_est(x.hi)}; }
RAYCAST_INLINE vint to_int(vfloat a) { return {half::to_int(a.lo), half::to_int(a.hi)}; }
// Lanes in the opposite order: each half reversed, the halves swapped.
RAYCAST_INLINE vfloat reverse(vfloat a) { return {half::reverse(a.hi), half::reverse(a.lo)}; }
RAYCAST_INLINE vint reverse(vint a) { return {half::reverse(a.hi), half::reverse(a.lo)}; }
RAYCAST_INLINE vint splat_int(int32_t x) { return {half::splat_int(x), half::splat_int(x)}; }
RAYCAST_INLINE vuint operator>>(vuint a, int n) { return {half::shr(a.lo, n), half::shr(a.hi, n)}; }
RAYCAST_INLINE vuint operator<<(vuint a, int n) { return {half::shl(a.lo, n), half::shl(a.hi, n)}; }
RAYCAST_INLINE vfloat to_float(vuint a) { return {half::to_float(a.lo), half::to_float(a.hi)}; }
RAYCAST_INLINE vuint as_uint(vfloat a) { return {half::as_uint(a.lo), half::as_uint(a.hi)}; }
RAYCAST_INLINE vfloat as_float(vuint a) { return {half::as_float(a.lo), half::as_float(a.hi)}; }
RAYCAST_INLINE vmask operator>(vuint a, vuint b) { return {half::gt_u(a.lo, b.lo), half::gt_u(a.hi, b.hi)}; }
RAYCAST_INLINE vuint select(vmask m, vuint a, vuint b) {
  return {half::select_u(m.lo, a.lo, b.lo), half::select_u(m.hi, a.hi, b.hi)};
}
