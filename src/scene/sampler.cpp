#include "scene/sampler.h"

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

// Dimension 0 of the Sobol sequence: the van der Corput sequence, index's
// bits reversed.
uint32_t sobol_dimension0(uint32_t index) {
  uint32_t x = 0;
  for (int b = 0; b < 32; ++b) x |= ((index >> b) & 1u) << (31 - b);
  return x;
}

// Dimension 1 (its generator matrix is Pascal's triangle mod 2; Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020, listing 1).
uint32_t sobol_dimension1(uint32_t index) {
  uint32_t v = 1u << 31, x = 0;
  for (; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}

}  // namespace

sample_table::sample_table(sampler_kind kind, uint32_t count, uint64_t seed) {
  plan_.kind = kind;
  plan_.count = count;
  plan_.seed_key = mix(uint32_t(seed) ^ mix(uint32_t(seed >> 32) + golden));
  uint32_t nx = 1;
  for (uint32_t d = 1; uint64_t(d) * d <= count; ++d)
    if (count % d == 0) nx = d;
  plan_.nx = nx;
  plan_.ny = count / nx;
  plan_.inv_nx = 1.0f / float(plan_.nx);
  plan_.inv_ny = 1.0f / float(plan_.ny);
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

namespace {
// Calls f with the sampler's kind as a template argument.
template <class F>
void with_kind(sampler_kind k, F&& f) {
  switch (k) {
    case sampler_kind::random: f.template operator()<sampler_kind::random>(); break;
    case sampler_kind::stratified: f.template operator()<sampler_kind::stratified>(); break;
    case sampler_kind::sobol: f.template operator()<sampler_kind::sobol>(); break;
  }
}
}  // namespace

void sample_offsets(const sample_plan& p, uint32_t i, uint32_t j, uint32_t s, float& xi, float& eta) {
  with_kind(p.kind, [&]<sampler_kind K>() { offsets<K>(p, seeds_for<K>(p, i, j), s, xi, eta); });
}

void sample_offset_counts(const sample_plan& p, uint32_t i, uint32_t j, uint32_t s, float& xi, float& eta) {
  with_kind(p.kind, [&]<sampler_kind K>() { offset_counts<K>(p, seeds_for<K>(p, i, j), s, xi, eta); });
}

float offset_unit_of(sampler_kind k) {
  float unit = 1.0f;
  with_kind(k, [&]<sampler_kind K>() { unit = offset_unit<K>; });
  return unit;
}

}  // namespace sampling
}  // namespace raycast
