#include "sampling/sampler.h"

#include <cmath>

namespace raycast {

std::string_view to_string(sampler_kind k) {
  switch (k) {
    case sampler_kind::random: return "random";
    case sampler_kind::stratified: return "stratified";
    case sampler_kind::sobol: return "sobol";
  }
  return "?";
}

std::optional<sampler_kind> parse_sampler(std::string_view text) {
  for (sampler_kind k : {sampler_kind::random, sampler_kind::stratified, sampler_kind::sobol})
    if (text == to_string(k)) return k;
  return std::nullopt;
}

namespace sampling {
namespace {

// Dimension 0 of the Sobol sequence: the van der Corput sequence, the index's bits reversed.
constexpr uint32_t sobol_dimension0(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Dimension 1 (its generator matrix is Pascal's triangle mod 2; Burley's Owen scrambling, listing 1).
constexpr uint32_t sobol_dimension1(uint32_t index) {
  uint32_t v = 1u << 31, x = 0;
  for (; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}

// The seed folded to 32 bits.
uint32_t seed_key_of(uint64_t seed) { return mix(uint32_t(seed) ^ mix(uint32_t(seed >> 32) + golden)); }

// The strata's columns for count samples: the largest divisor not above sqrt(count).
uint32_t strata_columns(uint32_t count) {
  uint32_t nx = 1;
  for (uint32_t d = 1; uint64_t(d) * d <= count; ++d)
    if (count % d == 0) nx = d;
  return nx;
}

// The first eight points of the Sobol sequence's two dimensions (constexpr).
struct sobol_eight {
  uint32_t x[8]{}, y[8]{};
  constexpr sobol_eight() {
    for (uint32_t q = 0; q < 8; ++q) x[q] = sobol_dimension0(q), y[q] = sobol_dimension1(q);
  }
};
constexpr sobol_eight eight;

// Sobol points [g0, g0 + m), the pixel's digital shift applied. A point is linear over GF(2) in its
// index's bits, so where g0 is a multiple of 8 and m <= 8, point g0 | q is point g0's xor point q's.
void sobol_numbers(const ao_seeds& px, uint32_t g0, uint32_t m, float* u1, float* u2) {
  if (g0 % 8 == 0 && m <= 8) {
    const uint32_t x0 = sobol_dimension0(g0) ^ px.a, y0 = sobol_dimension1(g0) ^ px.b;
    for (uint32_t q = 0; q < m; ++q) {
      u1[q] = float((x0 ^ eight.x[q]) >> 8) * 0x1p-24f;
      u2[q] = float((y0 ^ eight.y[q]) >> 8) * 0x1p-24f;
    }
    return;
  }
  for (uint32_t q = 0; q < m; ++q) {
    u1[q] = float((sobol_dimension0(g0 + q) ^ px.a) >> 8) * 0x1p-24f;
    u2[q] = float((sobol_dimension1(g0 + q) ^ px.b) >> 8) * 0x1p-24f;
  }
}

}  // namespace

ao_plan make_ao_plan(sampler_kind kind, uint32_t count, uint64_t seed) {
  const uint32_t nx = count > 0 ? strata_columns(count) : 1, ny = count > 0 ? count / nx : 1;
  return {kind, seed_key_of(seed), count, nx, ny, 1.0f / float(nx), 1.0f / float(ny)};
}

ao_seeds ao_pixel(const ao_plan& p, uint32_t i, uint32_t j) {
  const uint32_t key = mix(mix(mix(i ^ p.seed_key) + j * golden) ^ 0x2c1b3c6du);
  if (p.kind == sampler_kind::sobol) return {mix(key ^ 0x68bc21ebu), mix(key ^ 0x02e5be93u)};
  return {key, key};
}

void ao_numbers(const ao_plan& p, const ao_seeds& px, uint32_t s, uint32_t k0, uint32_t m, float* u1, float* u2) {
  const uint32_t g0 = s * p.count + k0;
  if (p.kind == sampler_kind::sobol) return sobol_numbers(px, g0, m, u1, u2);
  for (uint32_t q = 0; q < m; ++q) {
    const uint32_t r = mix(px.a + (g0 + q + 1) * golden), k = k0 + q;
    if (p.kind == sampler_kind::random) {
      u1[q] = float(r >> 8) * 0x1p-24f;
      u2[q] = float(mix(r ^ 0x297a2d39u) >> 8) * 0x1p-24f;
    } else {
      u1[q] = min((float(k % p.nx) + unit_high<float>(r)) * p.inv_nx, one_below);
      u2[q] = min((float(k / p.nx) + unit_low<float>(r)) * p.inv_ny, one_below);
    }
  }
}

void ao_numbers(const ao_plan& p, uint32_t i, uint32_t j, uint32_t s, uint32_t k, float& u1, float& u2) {
  ao_numbers(p, ao_pixel(p, i, j), s, k, 1, &u1, &u2);
}

sample_table::sample_table(sampler_kind kind, uint32_t count, uint64_t seed) {
  const uint32_t nx = strata_columns(count), ny = count / nx;
  plan_ = {kind, count, seed_key_of(seed), nx, ny, 1.0f / float(nx), 1.0f / float(ny), nullptr};
  slots_.resize(count);
  for (uint32_t s = 0; s < count; ++s) {
    sample_slot& sl = slots_[s];
    if (kind == sampler_kind::sobol) {
      sl.k0 = sobol_dimension0(s);
      sl.k1 = sobol_dimension1(s);
    } else {
      sl.k0 = (s + 1) * golden;
      sl.k1 = 0;
    }
    sl.sx = float(s % nx);
    sl.sy = float(s / nx);
  }
  plan_.slots = slots_.data();
}

void sample_offsets(const sample_plan& p, uint32_t i, uint32_t j, uint32_t s, float& xi, float& eta) {
  const auto at = [&]<sampler_kind K>() { offsets<K>(p, seeds_for<K>(p, i, j), s, xi, eta); };
  switch (p.kind) {
    case sampler_kind::random: at.template operator()<sampler_kind::random>(); break;
    case sampler_kind::stratified: at.template operator()<sampler_kind::stratified>(); break;
    case sampler_kind::sobol: at.template operator()<sampler_kind::sobol>(); break;
  }
}

}  // namespace sampling
}  // namespace raycast
