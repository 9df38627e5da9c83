// A hit's AO rays walked together: sphere_grid's DDA (grid.cpp) with each
// ray in a vector lane. A ray walked alone chooses at each step which face
// it leaves its cell by, a branch its random direction makes
// unpredictable; in lanes that choice is a mask. The cell the rays start
// in is every lane's: its spheres are tested against all the rays at once
// (first_cell_lanes). Past it, short rays (at most 4
// cells) test each lane's cells as the lone walk does, as the lane enters
// them (cell_occluded); long ones gather each lane's occupied cells and
// test them as the lone long walk does (cells_occluded), every lane's cells
// read ahead before any lane's are tested, so that four (or eight) rays'
// cache misses overlap.
//
// The lanes' boundaries are floats, the lone walk's doubles, and the
// boundary after k steps on an axis is first + k delta (a product, not a
// running sum, so that its error does not grow with the steps). In grid
// units (coordinates below 2, the segment within the grid's box, t below
// 4): the first boundary's place (lo + c h - o) is off by at most 2 float
// ulps of 2, 4.8e-7, and its t, divided by the direction's component, by
// that over the component and 2 ulps of t; k delta by 3 ulps of itself
// and the sum by 1: the ray at the computed t is off the boundary's plane
// by at most 4.8e-7 + 6 * 2^-24 * 4 = 1.9e-6, below 2^-17 (7.6e-6), a
// quarter of the spheres' widening (grid.cpp). So where the lanes' walk
// and the lone walk part (a ray within that of a cell's face) each cell
// one visits and the other not is one the segment passes within 2^-17 of,
// and lists every sphere the segment can meet there: a ray's verdict is
// the lone walk's, whatever its length. Four rays at a time (light/lanes.h),
// or eight where this file is compiled a second time, for AVX2: `width`
// below is that compilation's lanes::width, and it defines the walk for that
// width alone. It calls nothing a compiler could leave out of line but what
// grid.h forces inline, and no std:: function: <cmath>'s and <algorithm>'s
// helpers, out of line in an unoptimised build, would be AVX2 copies any
// caller might get.
#include <cstdint>

#include "light/grid.h"
#include "light/lanes.h"

namespace raycast {

using lanes::fvec;
using lanes::ivec;
using lanes::uvec;
using lanes::pick;
using lanes::bits_of;
using lanes::blocks_in_lanes;
constexpr int width = lanes::width;

// The walk's state, lane by lane: the ray's direction, the t of the first boundary on each
// axis, the t between two, the steps taken on each axis and the t of the
// next boundary (first + steps delta; infinity on an axis the ray does not
// move along), the steps left on each axis before the grid ends, the
// step's change of cell index on each axis and the cell's index.
template <>
struct sphere_grid::lanes_walk<width> {
  fvec dir[3], first[3], delta[3], steps[3] = {}, next[3];  // dir: each lane's direction (0 past the group)
  ivec left[3];
  uvec move[3], cell = {};  // unsigned: a lane that has ended may step on past the grid

  // From o, in the cell that holds it (o inside the grid's box).
  RAYCAST_INLINE lanes_walk(const sphere_grid& g, const float o[3], const float (*d)[3], int m) {
    const int stride[3] = {1, g.dims_[0], g.dims_[0] * g.dims_[1]};
    for (int a = 0; a < 3; ++a) {
      const float p = (o[a] - g.lo_[a]) * g.inv_h_;  // grid.cpp's walk at t0 = 0
      const int c = p <= 0.0f ? 0 : int(p) < g.dims_[a] - 1 ? int(p) : g.dims_[a] - 1;
      fvec& da = dir[a];
      da = fvec{};
      for (int l = 0; l < m; ++l) da[l] = d[l][a];
      // A component below the normal floats walks as 0 (its 1 / d would be
      // infinite): it moves the ray by less than 2^-125 over the walk.
      const ivec forward = ivec(da > 0.0f), still = ivec(pick(ivec(da < 0.0f), -da, da) < __FLT_MIN__);
      const fvec inv = 1.0f / da;
      const fvec boundary = (g.lo_[a] + __builtin_convertvector(ivec{} + c + (forward & 1), fvec) * g.h_) - o[a];
      const fvec inf = fvec{} + __builtin_inff();
      first[a] = next[a] = pick(still, inf, boundary * inv);
      delta[a] = pick(still, fvec{}, g.h_ * pick(ivec(inv < 0.0f), -inv, inv));
      left[a] = (forward & (g.dims_[a] - 1 - c)) | (~forward & c);
      move[a] = uvec((forward & stride[a]) | (~forward & -stride[a]));
      cell += uint32_t(c) * uint32_t(stride[a]);
    }
  }
  // Every lane to its next cell (the axis whose boundary is nearest, ties
  // as walk::step breaks them): bit l of the result is set where lane l's
  // segment (ending at `end`) or the grid ended first.
  RAYCAST_INLINE uint32_t step(const float end) {
    const ivec lt01 = ivec(next[0] < next[1]), lt02 = ivec(next[0] < next[2]), lt12 = ivec(next[1] < next[2]);
    const ivec along[3] = {lt01 & lt02, ~lt01 & lt12, ~((lt01 & lt02) | (~lt01 & lt12))};
    const fvec t = pick(along[0], next[0], pick(along[1], next[1], next[2]));
    for (int a = 0; a < 3; ++a) {
      left[a] += along[a];  // -1 on the axis stepped along
      cell += uvec(along[a]) & move[a];
      steps[a] += fvec(along[a] & ivec(fvec{} + 1.0f));
      next[a] = first[a] + steps[a] * delta[a];
    }
    return bits_of(ivec(t > end) | ((left[0] | left[1] | left[2]) < 0));
  }
};

// The cell a group starts in (every lane's: its rays share their origin):
// each of its spheres read once and tested against the group's k rays
// together, as blocks() tests it (lanes::blocks_in_lanes: the same bits),
// not once a ray (a box of random centres lists half a dozen spheres in a
// cell: its AO a quarter faster). Bit l: ray l is blocked; done once every
// ray is.
template <>
uint32_t sphere_grid::first_cell_lanes<width>(const lanes_walk<width>& w, const float o[3], int k, float tmax,
                                              uint32_t skip) const {
  const size_t c = w.cell[0];
  if (!occupied(c)) return 0;
  const uint32_t all = (1u << k) - 1;
  uint32_t hit = 0;
  const auto test = [&](uint32_t p) {
    const float* s = at(p);
    const fvec sphere[4] = {lanes::splat(s[0]), lanes::splat(s[1]), lanes::splat(s[2]), lanes::splat(s[3])};
    if (p != skip) hit |= bits_of(blocks_in_lanes(o, w.dir, sphere, tmax)) & all;
    return hit == all;
  };
  for (uint32_t p = home_[c]; p < home_[c + 1]; ++p)
    if (test(p)) return hit;
  for (uint32_t e = first_[c]; e < first_[c + 1]; ++e)
    if (test(refs_[e])) return hit;
  return hit;
}

// A group's short rays (the lanes `live`, past the first cell): each lane's
// cells tested as it enters them.
template <>
uint32_t sphere_grid::near_lanes<width>(lanes_walk<width>& w, const float o[3], const float (*d)[3], uint32_t live,
                                        float tmax, uint32_t skip) const {
  uint32_t hit = 0;
  while (live != 0) {
    live &= ~w.step(tmax);
    for (uint32_t b = live; b != 0; b &= b - 1) {
      const int l = __builtin_ctz(b);
      const size_t c = w.cell[l];
      if (occupied(c) && cell_occluded(c, o, d[l], tmax, skip)) hit |= 1u << l, live &= ~(1u << l);
    }
  }
  return hit;
}

// A group's long rays: each lane gathers its occupied cells until one has
// `ahead` (a round ends at the step that fills one lane, and a step adds at
// most one cell a lane, so none has more; each has room for twice that),
// then every lane's cells are read ahead before any lane's are tested
// (cells_occluded), so that the lanes' misses overlap.
template <>
uint32_t sphere_grid::far_lanes<width>(lanes_walk<width>& w, const float o[3], const float (*d)[3], uint32_t live,
                                       float tmax, uint32_t skip) const {
  size_t found[width][2 * ahead];
  int count[width] = {};
  uint32_t hit = 0;
  const auto gather = [&](int l, size_t c) {
    found[l][count[l]] = c;
    count[l] += int(occupied(c));
    __builtin_prefetch(&home_[c]);
    __builtin_prefetch(&first_[c]);
  };
  for (uint32_t walking = live; live != 0;) {
    bool full = false;
    while (walking != 0 && !full) {
      walking &= ~w.step(tmax);
      for (uint32_t b = walking; b != 0; b &= b - 1) {
        const int l = __builtin_ctz(b);
        gather(l, w.cell[l]);
        full |= count[l] >= ahead;
      }
    }
    for (uint32_t b = live; b != 0; b &= b - 1) read_ahead(found[__builtin_ctz(b)], count[__builtin_ctz(b)]);
    for (uint32_t b = live; b != 0; b &= b - 1) {
      const int l = __builtin_ctz(b);
      if (count[l] > 0 && cells_occluded(found[l], count[l], o, d[l], tmax, skip)) hit |= 1u << l;
      count[l] = 0;
    }
    live &= walking & ~hit;
    walking &= live;
  }
  return hit;
}

// occluded()'s group (rays from inside the box, in a grid that walks in
// lanes), `width` rays a walk.
template <>
uint32_t sphere_grid::lanes_occluded<width>(const float o[3], const float (*d)[3], int m, float tmax,
                                            uint32_t skip) const {
  uint32_t blocked = 0;
  for (int l0 = 0; l0 < m; l0 += width) {
    const int k = m - l0 < width ? m - l0 : width;
    lanes_walk<width> w(*this, o, d + l0, k);
    const uint32_t all = (1u << k) - 1, first = first_cell_lanes(w, o, k, tmax, skip);
    const uint32_t rest = tmax <= 4 * h_ ? near_lanes(w, o, d + l0, all & ~first, tmax, skip)
                                         : far_lanes(w, o, d + l0, all & ~first, tmax, skip);
    blocked |= (first | rest) << l0;
  }
  return blocked;
}

}  // namespace raycast
