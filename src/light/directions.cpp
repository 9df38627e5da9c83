// The AO rays' directions (light/secondary.h): cosine-weighted about a
// normal, their turn from a table and a short series in float operations
// alone, four to a vector (light/lanes.h's four-float type, whatever the
// build), so that every machine and backend gives the same bits.
#include "light/directions.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "light/frame.h"
#include "light/lanes.h"
#include "light/secondary.h"

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
lanes::f4 turn_at(const float* table, lanes::i4 i) {
  lanes::f4 v;
  for (int l = 0; l < 4; ++l) v[l] = table[i[l]];
  return v;
}
int whole_of(float x) { return int(x); }
lanes::i4 whole_of(lanes::f4 x) { return __builtin_convertvector(x, lanes::i4); }
float float_of(int i) { return float(i); }
lanes::f4 float_of(lanes::i4 i) { return __builtin_convertvector(i, lanes::f4); }
float sqrt_of(float x) { return std::sqrt(x); }
lanes::f4 sqrt_of(lanes::f4 x) { return lanes::sqrt(x); }

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

}  // namespace

// ao_direction of m numbers in a frame (t, b) about n, four to a vector.
void ao_directions_in_frame(const float n[3], const float t[3], const float bt[3], const float* u1, const float* u2,
                         uint32_t m, float (*dir)[3]) {
  constexpr uint32_t width = 4;
  for (uint32_t v0 = 0; v0 < m; v0 += width) {
    const uint32_t k = std::min(width, m - v0);
    lanes::f4 x = {}, y = {}, d[3];
    for (uint32_t q = 0; q < k; ++q) x[q] = u1[v0 + q], y[q] = u2[v0 + q];
    direction_in_frame(n, t, bt, x, y, d);
    for (uint32_t q = 0; q < k; ++q)
      for (int c = 0; c < 3; ++c) dir[v0 + q][c] = d[c][q];
  }
}

void unit_circle(float u, float& c, float& s) { turn_of(u, c, s); }

void ao_direction(const float n[3], float u1, float u2, float dir[3]) {
  float t[3], bt[3];
  frame_about(n, t, bt);
  direction_in_frame<float>(n, t, bt, u1, u2, dir);
}

void ao_directions(const float n[3], const float* u1, const float* u2, uint32_t m, float (*dir)[3]) {
  float t[3], bt[3];
  frame_about(n, t, bt);
  ao_directions_in_frame(n, t, bt, u1, u2, m, dir);
}

}  // namespace raycast
