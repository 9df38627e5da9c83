#include "light/secondary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "light/frame.h"
#include "light/lanes.h"
#include "scene/sphere.h"

namespace raycast {

namespace {

// cos and sin of x in [0, pi/4], in double: their Taylor series to x^16
// and x^17 (the next terms below 1e-17 of them).
void eighth_turn(double x, double& c, double& s) {
  double term_c = 1.0, term_s = x;
  c = 0.0, s = 0.0;
  for (int k = 0; k <= 8; ++k) {
    c += term_c, s += term_s;
    term_c *= -x * x / double((2 * k + 1) * (2 * k + 2));
    term_s *= -x * x / double((2 * k + 2) * (2 * k + 3));
  }
}

// cos and sin of the turns i / 256, rounded to float: the octant's from
// eighth_turn, the rest by symmetry (exact: 0 and 1 at the quarters).
struct turn_table {
  float c[256], s[256];
  turn_table() {
    for (int i = 0; i < 256; ++i) {
      const int q = i / 64, r = i % 64;  // the quarter and the 256ths within it
      const bool fold = r > 32;           // cos(pi/2 f) = sin(pi/2 (1 - f))
      double c0 = 0, s0 = 0;
      eighth_turn((fold ? 64 - r : r) * (2.0 * 3.14159265358979323846 / 256.0), c0, s0);
      if (fold) std::swap(c0, s0);
      const double cq[4] = {c0, -s0, -c0, s0}, sq[4] = {s0, c0, -s0, -c0};
      c[i] = float(cq[q]), s[i] = float(sq[q]);
    }
  }
};
const turn_table turns;

}  // namespace

namespace {

// A turn's table entry, the whole part of a float and its float: of one
// number, or of a vector's lanes (light/lanes.h) with the same roundings.
float turn_at(const float* table, int i) { return table[i]; }
lanes::fvec turn_at(const float* table, lanes::ivec i) {
  lanes::fvec v;
  for (int l = 0; l < lanes::width; ++l) v[l] = table[i[l]];
  return v;
}
int whole_of(float x) { return int(x); }
lanes::ivec whole_of(lanes::fvec x) { return __builtin_convertvector(x, lanes::ivec); }
float float_of(int i) { return float(i); }
lanes::fvec float_of(lanes::ivec i) { return __builtin_convertvector(i, lanes::fvec); }
float sqrt_of(float x) { return std::sqrt(x); }
lanes::fvec sqrt_of(lanes::fvec x) { return lanes::sqrt(x); }

// unit_circle of a float or of a vector's lanes. u = (i + f) / 256: the
// table's turn i / 256, and a small angle d = 2 pi f / 256 < 0.0246 (f
// exact) by its series: 1 - cos d and sin d to d^4 and d^3 (the next terms
// below 8e-11), added to the table's values as corrections, so that only the
// table's rounding and the last addition's round at the scale of the result.
// No branch: AO rays' turns are random, and a mispredicted quarter costs
// more than the arithmetic.
template <class F>
void turn_of(F u, F& c, F& s) {
  const F x = u * 256.0f;  // exact
  const auto whole = whole_of(x);
  const F d = (x - float_of(whole)) * 0.0245436926f;  // 2 pi / 256
  const F d2 = d * d;
  const F one_less_cos = d2 * (0.5f - d2 * (1.0f / 24)), sin_d = d * (1.0f - d2 * (1.0f / 6));
  const F c0 = turn_at(turns.c, whole & 255), s0 = turn_at(turns.s, whole & 255);
  c = c0 - (c0 * one_less_cos + s0 * sin_d);
  s = s0 + (c0 * sin_d - s0 * one_less_cos);
}

// ao_direction in a frame (t, b) about n made once for a hit's rays: of one
// pair of numbers, or of a vector's lanes.
template <class F>
void direction_in_frame(const float n[3], const float t[3], const float bt[3], F u1, F u2, F dir[3]) {
  F cos_phi, sin_phi;
  turn_of(u1, cos_phi, sin_phi);
  const F rad = sqrt_of(u2);
  const F x = rad * cos_phi, y = rad * sin_phi, z = sqrt_of(1.0f - u2);
  for (int k = 0; k < 3; ++k) dir[k] = (x * t[k] + y * bt[k]) + z * n[k];
}

// ao_direction of m numbers in a frame (t, b) about n, four to a vector.
void directions_in_frame(const float n[3], const float t[3], const float bt[3], const float* u1, const float* u2,
                         uint32_t m, float (*dir)[3]) {
  constexpr uint32_t width = lanes::width;
  for (uint32_t v0 = 0; v0 < m; v0 += width) {
    const uint32_t k = std::min(width, m - v0);
    lanes::fvec x = {}, y = {}, d[3];
    for (uint32_t q = 0; q < k; ++q) x[q] = u1[v0 + q], y[q] = u2[v0 + q];
    direction_in_frame(n, t, bt, x, y, d);
    for (uint32_t q = 0; q < k; ++q)
      for (int c = 0; c < 3; ++c) dir[v0 + q][c] = d[c][q];
  }
}

}  // namespace

void unit_circle(float u, float& c, float& s) { turn_of(u, c, s); }

void ao_direction(const float n[3], float u1, float u2, float dir[3]) {
  float t[3], bt[3];
  frame_about(n, t, bt);
  direction_in_frame<float>(n, t, bt, u1, u2, dir);
}

void ao_directions(const float n[3], const float* u1, const float* u2, uint32_t m, float (*dir)[3]) {
  float t[3], bt[3];
  frame_about(n, t, bt);
  directions_in_frame(n, t, bt, u1, u2, m, dir);
}

namespace {

// How many of a hit's AO rays reach their distance: their directions made
// a group at a time, four to a vector (light/lanes.h), before any is
// walked, and the group walked together (sphere_grid::occluded).
uint32_t open_ao_rays(const secondary_rays& r, const lit_lanes& ls, int l, const float n[3], const float p[3],
                      uint32_t skip) {
  constexpr uint32_t group = sphere_grid::group;
  float t[3], bt[3];
  frame_about(n, t, bt);
  const sampling::ao_seeds seeds = sampling::ao_pixel(r.ao, uint32_t(ls.i0 + l), uint32_t(ls.j));
  uint32_t open = 0;
  for (uint32_t a0 = 0; a0 < r.ao.count; a0 += group) {
    const uint32_t m = std::min(group, r.ao.count - a0);
    float u1[group], u2[group], dir[group][3];
    sampling::ao_numbers(r.ao, seeds, ls.sample, a0, m, u1, u2);
    directions_in_frame(n, t, bt, u1, u2, m, dir);
    open += m - uint32_t(__builtin_popcount(r.grid->occluded(p, dir, int(m), r.ao_distance, skip)));
  }
  return open;
}

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
  if (r.ao.count > 0) ambient = float(open_ao_rays(r, ls, l, n, p, skip)) / float(r.ao.count);
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
