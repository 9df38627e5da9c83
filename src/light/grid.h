// The structure secondary rays ask: a uniform grid over the spheres, built
// only when a render casts shadow or ambient-occlusion rays. Those rays
// start anywhere and go anywhere, so the primary rays' row index (which
// serves rays from the camera only) cannot answer them.
//
// The spheres are kept in the grid's own frame: world minus `origin` (the
// middle of the spheres' bounding box), times 2^-scale_exp (a power of two
// that brings the box into [-1, 1]: exact, so a scene at 1e-20 or 1e20 gives
// the same float bits as at 1), rounded to float once. Each sphere is listed
// in every cell its bounding box (widened by 2^-16 of the grid's size, far
// above the queries' rounding: grid_lanes.cpp's float walk strays by less than
// 2^-17) overlaps: the spheres are stored in the order
// of their centres' (home) cells, so a cell's own spheres are one run of
// them, and only the spheres reaching in from other cells are referenced.
// About N cells for N spheres, at most 2^31 listings; a scene of a few huge spheres among small ones
// (whose boxes would list them in most cells) gets a coarser grid.
//
// Memory: 20 bytes a sphere (centre, radius and position), 4 bytes a
// reference from another cell (up to 7 a sphere in a packed box, almost
// none in the bench's lattice-jittered box, about half a sphere in its
// clouds) and
// 8 bytes a cell (about one a sphere): 30 to 60 bytes a sphere.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "memory/arrays.h"
#include "scene/scene.h"
#include "simd/inline.h"

namespace raycast {

class sphere_grid {
 public:
  sphere_grid() = default;
  // Over every sphere of s; without `cells`, the spheres alone (in the
  // grid's frame, for shadow_bins), and occluded() is never asked. Built
  // on `threads` threads: the same grid on any number.
  explicit sphere_grid(const scene& s, bool cells = true, int threads = 1);
  bool has_cells() const { return !first_.empty(); }

  // A ray's mean free path among the spheres, in mean spacings: the box's
  // volume over the spheres' total cross-section pi r^2, divided by the
  // cube root of the volume a sphere. About 1.8 in a box packed at 0.3,
  // 30 and more in the bench's clouds. Below short_free_path a ray meets a
  // sphere (or leaves) within a few cells, and the renderer's shadow rays
  // walk the cells, where it built them, instead of asking light-space
  // bins (light/README.md).
  double free_path() const { return free_path_; }
  static constexpr double short_free_path = 3;

  // Whether the segment o + t d, t in [0, tmax] (grid units; d of unit
  // length), meets a sphere's solid ball other than sphere `skip` (its
  // index in the scene): a ray that starts inside a sphere is blocked by
  // it. Grid units: world * 2^-scale_exp.
  bool occluded(const float o[3], const float d[3], float tmax, uint32_t skip) const;
  // occluded() for m <= 8 rays from one origin (a hit's AO rays): bit a of
  // the result is occluded(o, d[a], tmax, skip). Rays from inside the
  // grid's box walk together, one a vector lane (light/README.md), so that
  // no branch waits on which face each ray leaves its cell by, and long
  // rays' cache misses overlap.
  // The lanes are `lanes` floats wide: 4 (the build's baseline: SSE2, NEON)
  // or 8 (AVX2, on x86-64, where the CPU runs it); 0 (or 8 where the CPU
  // does not) takes the widest of lane_widths(). Every width gives the same
  // bits.
  static constexpr int group = 8;
  uint32_t occluded(const float o[3], const float (*d)[3], int m, float tmax, uint32_t skip, int lanes = 0) const;
  // Whether a group's rays from inside the box walk in lanes.
  bool walks_in_lanes() const { return h_ <= 0.5f && cells() < size_t(1) << 31; }
  // The lane widths this build has and this CPU runs (RAYCAST_MAX_ISA
  // below avx2 leaves 4 alone), narrowest first.
  static const std::vector<int>& lane_widths();

  // Sphere k's (its index in the scene) centre (grid frame) and radius (grid
  // units), x y z r. The spheres are stored in the order of the cells their
  // centres lie in (with cells: the spheres a ray meets together lie
  // together in memory), at position(k); at(p) reads position p.
  const float* sphere(uint32_t k) const { return at(position(k)); }
  uint32_t position(uint32_t k) const { return rank_.empty() ? k : rank_[k]; }
  RAYCAST_INLINE const float* at(uint32_t p) const { return &spheres_[size_t(p) * 4]; }
  size_t size() const { return spheres_.size() / 4; }
  // The median radius of up to 4096 spheres spread over the scene: the
  // structures' cells are no smaller than its diameter, so that a packed
  // scene's spheres are listed a few times each, not dozens.
  double typical_radius() const;

  // Whether the segment o + t d, t in [0, tmax], meets the solid ball of
  // the sphere at position p (light/secondary.h's rule): a start inside it,
  // or the near root of a sphere ahead within tmax, from Hearn and Baker's
  // squared distance of the line from the centre (no cancellation against
  // |o - c|^2).
  RAYCAST_INLINE bool blocks(uint32_t p, const float o[3], const float d[3], float tmax) const {
    const float* s = at(p);
    const float ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
    const float r2 = s[3] * s[3];
    if ((ox * ox + oy * oy) + oz * oz <= r2) return true;
    const float b = (ox * d[0] + oy * d[1]) + oz * d[2];
    if (b >= 0.0f) return false;  // outside, and moving away
    const float vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
    const float m2 = (vx * vx + vy * vy) + vz * vz;
    return m2 <= r2 && -b - __builtin_sqrtf(r2 - m2) <= tmax;  // std::sqrt's, with no call left out of line
  }
  double origin[3] = {0, 0, 0};
  int scale_exp = 0;  // grid units = world units * 2^-scale_exp

  size_t cells() const { return first_.empty() ? 0 : first_.size() - 1; }
  float cell_side() const { return h_; }  // grid units
  // Listings: each sphere in its home cell, and in every other cell it overlaps.
  size_t references() const { return size() + refs_.size(); }
  size_t bytes() const {
    return spheres_.size() * 4 + rank_.size() * 4 + home_.size() * 4 + first_.size() * 4 + refs_.size() * 4 +
           occupied_.size() * 8;
  }

 private:
  void build_cells(const double lo[3], const double hi[3]);
  void sort_by_home_cell(double h);
  // Cell c's spheres, its own and those referenced from other cells, as
  // positions in out[0 .. 8), the referenced ones prefetched: their count,
  // or -1 where either run is longer than 4. A run of up to 4 is copied
  // whole and its count added, with no loop: the runs' lengths (0 to a few)
  // are branches a long walk cannot predict.
  int listed(size_t c, uint32_t out[8]) const {
    const uint32_t h0 = home_[c], nh = home_[c + 1] - h0, f0 = first_[c], nf = first_[c + 1] - f0;
    if (nh > 4 || nf > 4) return -1;
    for (uint32_t l = 0; l < 4; ++l) out[l] = h0 + l;
    uint32_t tail[4] = {};
    const uint32_t* r = refs_.data() + f0;
    if (f0 + 4 > refs_.size()) r = std::copy(r, r + nf, tail) - nf;  // the array's last few
    for (uint32_t l = 0; l < 4; ++l) out[nh + l] = r[l];
    for (uint32_t l = 0; l < nf; ++l) __builtin_prefetch(at(r[l]));
    return int(nh + nf);
  }
  // Whether a sphere of cell c but skip blocks the segment: its own spheres
  // read in one run, then those reaching in from other cells.
  RAYCAST_INLINE bool cell_occluded(size_t c, const float o[3], const float d[3], float tmax, uint32_t skip) const {
    for (uint32_t p = home_[c]; p < home_[c + 1]; ++p)
      if (p != skip && blocks(p, o, d, tmax)) return true;
    for (uint32_t e = first_[c]; e < first_[c + 1]; ++e)
      if (refs_[e] != skip && blocks(refs_[e], o, d, tmax)) return true;
    return false;
  }
  RAYCAST_INLINE bool occupied(size_t c) const { return occupied_[c >> 6] >> (c & 63) & 1u; }
  struct walk;
  // grid_lanes.cpp, compiled once a width (light/lanes.h): each compilation
  // instantiates these for its own W alone. What it calls of the members
  // above is forced inline (at, blocks, cell_occluded, occupied): a copy the
  // AVX2 compilation left out of line could stand in for everyone's
  // (Build.TargetObjectsShareNoWeakSymbols).
  template <int W>
  struct lanes_walk;
  template <int W>
  uint32_t lanes_occluded(const float o[3], const float (*d)[3], int m, float tmax, uint32_t skip) const;
  template <int W>
  uint32_t first_cell_lanes(const lanes_walk<W>& w, const float o[3], int k, float tmax, uint32_t skip) const;
  template <int W>
  uint32_t near_lanes(lanes_walk<W>& w, const float o[3], const float (*d)[3], uint32_t live, float tmax,
                      uint32_t skip) const;
  template <int W>
  uint32_t far_lanes(lanes_walk<W>& w, const float o[3], const float (*d)[3], uint32_t live, float tmax,
                     uint32_t skip) const;
  bool any_blocks(uint32_t* list, int n, const float o[3], const float d[3], float tmax, uint32_t skip) const;
  static constexpr int ahead = 8;  // occupied cells a long walk gathers before it tests them
  bool far_occluded(walk& w, const float o[3], const float d[3], float tmax, uint32_t skip) const;
  void read_ahead(const size_t* found, int m) const;
  bool long_cell_occluded(size_t c, const float o[3], const float d[3], float tmax, uint32_t skip) const;
  bool cells_occluded(const size_t* found, int m, const float o[3], const float d[3], float tmax, uint32_t skip) const;

  float lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
  float h_ = 1, inv_h_ = 1;  // the cell's side, and 1 / it
  int dims_[3] = {0, 0, 0};
  double free_path_ = 0;
  int threads_ = 1;
  out_of_order_array<float> spheres_;   // 4 per sphere, by position
  out_of_order_array<uint32_t> rank_;   // with cells: each sphere's position (empty: the scene's order)
  // Cell c lists the spheres at positions home_[c] .. home_[c + 1] (those
  // whose centres it holds: read in one run, no reference), and the
  // positions refs_[first_[c] .. first_[c + 1]) (spheres from other cells
  // that overlap it, in ascending order).
  out_of_order_array<uint32_t> home_;   // cells + 1
  out_of_order_array<uint32_t> first_;  // cells + 1
  out_of_order_array<uint32_t> refs_;
  out_of_order_array<uint64_t> occupied_;  // bit c: cell c lists a sphere (a sparse scene's walk reads 1 bit an empty cell)
};

// grid_lanes.cpp's walks, one compilation a width (light/lanes.h).
template <>
uint32_t sphere_grid::lanes_occluded<4>(const float o[3], const float (*d)[3], int m, float tmax, uint32_t skip) const;
template <>
uint32_t sphere_grid::lanes_occluded<8>(const float o[3], const float (*d)[3], int m, float tmax, uint32_t skip) const;

}  // namespace raycast
