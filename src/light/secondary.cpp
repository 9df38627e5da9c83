#include "light/secondary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "light/frame.h"
#include "scene/sphere.h"

namespace raycast {

namespace {

// cos and sin of x in [0, pi/4]: their Taylor series to x^10 and x^9 (the
// next terms below 2e-9).
void eighth_turn(float x, float& c, float& s) {
  const float x2 = x * x;
  s = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
}

}  // namespace

void unit_circle(float u, float& c, float& s) {
  const float x = 4.0f * u;  // exact: the quarter turn and the fraction of it
  const int q = int(x);
  const float f = x - float(q);
  const bool fold = f > 0.5f;  // cos(pi/2 f) = sin(pi/2 (1 - f))
  float c0, s0;
  eighth_turn((fold ? 1.0f - f : f) * 1.57079632679489661923f, c0, s0);
  if (fold) std::swap(c0, s0);
  switch (q & 3) {
    case 0: c = c0, s = s0; break;
    case 1: c = -s0, s = c0; break;
    case 2: c = -c0, s = -s0; break;
    default: c = s0, s = -c0; break;
  }
}

void ao_direction(const float n[3], float u1, float u2, float dir[3]) {
  float t[3], bt[3];
  frame_about(n, t, bt);
  float cos_phi, sin_phi;
  unit_circle(u1, cos_phi, sin_phi);
  const float rad = std::sqrt(u2);
  const float x = rad * cos_phi, y = rad * sin_phi, z = std::sqrt(1.0f - u2);
  for (int k = 0; k < 3; ++k) dir[k] = (x * t[k] + y * bt[k]) + z * n[k];
}

namespace {

// Lane l's secondary rays' origin P = C + r n_out (n_out the outward
// normal: the faced one, turned back inside).
void origin_of(const secondary_rays& r, const lit_lanes& ls, int l, float p[3]) {
  const float* s = r.grid->sphere(ls.sphere[l]);
  const bool inside = (ls.inside >> l) & 1u;
  for (int c = 0; c < 3; ++c) p[c] = s[c] + s[3] * (inside ? -ls.n[c][l] : ls.n[c][l]);
}

// A batch's rays, their first reads done together (prefetched step by step
// over the lanes), so that their cache misses overlap instead of following
// one another: the hit spheres, then the shadow rays' cells and lists.
struct batch_rays {
  float p[lit_lanes::most][3];  // each lit lane's origin
  uint32_t shadowed = 0;         // bit l: lane l casts a shadow ray (through the bins: q[l])
  shadow_bins::query q[lit_lanes::most];

  batch_rays(const secondary_rays& r, const lit_lanes& ls) {
    for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
      const int l = __builtin_ctz(bits);
      __builtin_prefetch(r.grid->sphere(ls.sphere[l]));
      if (r.shadows && ls.diffuse[l] > 0.0f) shadowed |= bits & -bits;
    }
    for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) origin_of(r, ls, __builtin_ctz(bits), p[__builtin_ctz(bits)]);
    if (!r.bins) return;
    for (uint32_t bits = shadowed; bits != 0; bits &= bits - 1) {
      const int l = __builtin_ctz(bits);
      q[l] = r.bins->locate(p[l]);
      r.bins->prefetch(q[l], 0);
    }
    for (uint32_t bits = shadowed; bits != 0; bits &= bits - 1) r.bins->prefetch(q[__builtin_ctz(bits)], 1);
  }
};

// One lane: S and A, and the light they make.
float light_lane(const secondary_rays& r, const lit_lanes& ls, const batch_rays& b, int l) {
  const sphere_grid& g = *r.grid;
  const float n[3] = {ls.n[0][l], ls.n[1][l], ls.n[2][l]};
  const float* p = b.p[l];
  const uint32_t skip = (ls.inside >> l) & 1u ? uint32_t(-1) : ls.sphere[l];
  float shadow = 1.0f;
  if ((b.shadowed >> l) & 1u &&
      (r.bins ? r.bins->occluded(b.q[l], p, skip) : g.occluded(p, r.light, std::numeric_limits<float>::infinity(), skip)))
    shadow = 0.0f;
  float ambient = 1.0f;
  if (r.ao.count > 0) {
    uint32_t open = 0;
    const sampling::ao_seeds seeds = sampling::ao_pixel(r.ao, uint32_t(ls.i0 + l), uint32_t(ls.j));
    for (uint32_t a = 0; a < r.ao.count; ++a) {
      float u1, u2, dir[3];
      sampling::ao_numbers(r.ao, seeds, ls.sample, a, u1, u2);
      ao_direction(n, u1, u2, dir);
      if (!g.occluded(p, dir, r.ao_distance, skip)) ++open;
    }
    ambient = float(open) / float(r.ao.count);
  }
  return lit_ambient * ambient + (lit_diffuse * ls.diffuse[l]) * shadow;
}

}  // namespace

void light_lanes(const secondary_rays& r, const lit_lanes& ls, float light[lit_lanes::most]) {
  const batch_rays b(r, ls);
  for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
    const int l = __builtin_ctz(bits);
    light[l] = light_lane(r, ls, b, l);
  }
}

}  // namespace raycast
