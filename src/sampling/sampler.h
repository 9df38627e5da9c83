// Where a pixel's samples fall (the book's ch. 7), written once for a lane type (uint32_t and
// float, or a vector layer's vuint and vfloat) so every backend draws the same bits. Sample s of
// pixel (i, j) (j = 0 at the bottom) lies at (i + xi, j + eta), xi and eta in [0, 1), as the book's
// u = (i + random_double()) / (W - 1). Every number is a hash of (seed, pixel, sample index), so a
// pixel's samples are the same in any thread, band, region, backend or order (Wellons' lowbias32):
//   key(i, j)   = mix(mix(i ^ seed_key) + j * golden)          per pixel
//   random(s)   = mix(key + (s + 1) * golden)                  per sample (golden = 2^32 / phi)
// one hash giving both offsets, xi its high 16 bits, eta its low 16.
// - random: xi, eta from random(s), the book's choice.
// - stratified: an nx x ny grid, nx the largest divisor of N not above sqrt(N), sample s in
//   stratum (s mod nx, s div nx), jittered within it by random(s).
// - sobol: the first N points of the 2-D Sobol sequence (24 bits), each dimension's bits xor a
//   per-pixel seed mix(key ^ constant): a digital shift, which keeps the net property.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace raycast {

enum class sampler_kind : uint8_t { random, stratified, sobol };
// The sampler with the lowest error for its run time on the bench's scenes (bench/README.md).
inline constexpr sampler_kind default_sampler = sampler_kind::sobol;
std::string_view to_string(sampler_kind k);
std::optional<sampler_kind> parse_sampler(std::string_view text);

namespace sampling {

inline constexpr uint32_t golden = 0x9e3779b9u;
inline constexpr float one_below = 0x1.fffffep-1f;  // the largest float below 1

// The scalar lane type's operations, as the vector layers spell them.
inline float to_float(uint32_t x) { return float(x); }
inline float min(float a, float b) { return a < b ? a : b; }

// lowbias32 (Chris Wellons, "Prospecting for hash functions").
template <class U>
inline U mix(U x) {
  x = x ^ (x >> 16);
  x = x * U(0x7feb352du);
  x = x ^ (x >> 15);
  x = x * U(0x846ca68bu);
  return x ^ (x >> 16);
}

// The high and the low 16 bits as floats in [0, 1).
template <class F, class U>
inline F unit_high(U bits) {
  return F(to_float(bits >> 16)) * F(0x1p-16f);
}
template <class F, class U>
inline F unit_low(U bits) {
  return F(to_float(bits & U(0xffffu))) * F(0x1p-16f);
}

// Sample s's constants, the same for every pixel: random and stratified add k0 = (s + 1) golden to
// the pixel's key, stratified's stratum is (sx, sy); sobol's k0, k1 are its two dimensions' values.
struct sample_slot {
  uint32_t k0, k1;
  float sx, sy;
};

// Everything a render's samples depend on but the pixel.
struct sample_plan {
  sampler_kind kind = sampler_kind::random;
  uint32_t count = 1;
  uint32_t seed_key = 0;
  uint32_t nx = 1, ny = 1;           // stratified: the grid
  float inv_nx = 1.0f, inv_ny = 1.0f;  // 1 / nx, 1 / ny in float
  const sample_slot* slots = nullptr;  // count entries
};

// The per-pixel state: the key, or sobol's two digital shifts.
template <class U>
struct pixel_seeds {
  U a, b;
};

template <sampler_kind K, class U>
inline pixel_seeds<U> seeds_for(const sample_plan& p, U i, uint32_t j) {
  const U key = mix(mix(i ^ U(p.seed_key)) + U(j * golden));
  if constexpr (K == sampler_kind::sobol) return {mix(key ^ U(0x68bc21ebu)), mix(key ^ U(0x02e5be93u))};
  else return {key, key};
}

// The offsets as counts of a unit, xi = xi_count * offset_unit<K> exactly (stratified's are not
// counts: unit 1); the float renderers fold the power-of-two unit into their steps.
template <sampler_kind K>
inline constexpr float offset_unit = K == sampler_kind::sobol ? 0x1p-24f : K == sampler_kind::random ? 0x1p-16f : 1.0f;

template <sampler_kind K, class F, class U>
inline void offset_counts(const sample_plan& p, const pixel_seeds<U>& px, uint32_t s, F& xi, F& eta) {
  const sample_slot& sl = p.slots[s];
  if constexpr (K == sampler_kind::random) {
    const U r = mix(px.a + U(sl.k0));
    xi = F(to_float(r >> 16));
    eta = F(to_float(r & U(0xffffu)));
  } else if constexpr (K == sampler_kind::stratified) {
    // (stratum + jitter) / strata, kept below 1 where it rounds up to it.
    const U r = mix(px.a + U(sl.k0));
    xi = min((F(sl.sx) + unit_high<F>(r)) * F(p.inv_nx), F(one_below));
    eta = min((F(sl.sy) + unit_low<F>(r)) * F(p.inv_ny), F(one_below));
  } else {
    xi = F(to_float((U(sl.k0) ^ px.a) >> 8));
    eta = F(to_float((U(sl.k1) ^ px.b) >> 8));
  }
}

// Sample s's offsets (xi, eta) within the pixel, in [0, 1).
template <sampler_kind K, class F, class U>
inline void offsets(const sample_plan& p, const pixel_seeds<U>& px, uint32_t s, F& xi, F& eta) {
  offset_counts<K>(p, px, s, xi, eta);
  if constexpr (offset_unit<K> != 1.0f) {
    xi = xi * F(offset_unit<K>);
    eta = eta * F(offset_unit<K>);
  }
}

// The plan and its per-sample table, owned.
class sample_table {
 public:
  sample_table(sampler_kind kind, uint32_t count, uint64_t seed);
  const sample_plan& plan() const { return plan_; }

 private:
  std::vector<sample_slot> slots_;
  sample_plan plan_;
};

// Ambient occlusion's numbers (light/README.md): (u1, u2) in [0, 1) of ray k of the `count` rays
// from the hit of sample s of pixel (i, j), counter-based as the offsets are. A pixel's rays are
// one sequence, g = s count + k, keyed by the pixel's key xor a constant of their own:
// - random: u1, u2 from two hashes of (key + (g + 1) golden), 24 bits each;
// - stratified: each sample's rays in an nx x ny grid, jittered by that hash's 16-bit halves;
// - sobol: points g of the 2-D Sobol sequence, a digital shift per pixel.
struct ao_plan {
  sampler_kind kind = sampler_kind::sobol;
  uint32_t seed_key = 0, count = 0, nx = 1, ny = 1;
  float inv_nx = 1.0f, inv_ny = 1.0f;
};
ao_plan make_ao_plan(sampler_kind kind, uint32_t count, uint64_t seed);
void ao_numbers(const ao_plan& p, uint32_t i, uint32_t j, uint32_t s, uint32_t k, float& u1, float& u2);
// The same in two steps: the pixel's seeds, then rays [k0, k0 + m) of the hit.
struct ao_seeds {
  uint32_t a, b;
};
ao_seeds ao_pixel(const ao_plan& p, uint32_t i, uint32_t j);
void ao_numbers(const ao_plan& p, const ao_seeds& px, uint32_t s, uint32_t k0, uint32_t m, float* u1, float* u2);

// (xi, eta) of sample s of pixel (i, j), for the double reference and tests.
void sample_offsets(const sample_plan& p, uint32_t i, uint32_t j, uint32_t s, float& xi, float& eta);

}  // namespace sampling
}  // namespace raycast
