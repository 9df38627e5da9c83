// The shadow rays of a directional light are parallel: every one runs
// along L. So the spheres are binned once in the light's own orthographic
// view (the "irregular z-buffer" idea of Johnson et al. and Wyman et al.):
// a 2-D grid over the plane across L, each sphere listed in every cell its
// disc (widened by 2^-20 of the grid) overlaps, each cell's list sorted by
// how far along L the sphere reaches, C . L + r. A shadow ray from P looks
// up the one cell that P's projection falls in and tests its spheres from
// the far end of the list down with the grid's own test (light/grid.h),
// stopping at the first that blocks or that ends before P
// (C . L + r < P . L: it and the rest lie wholly behind it). Only the
// candidates differ from the 3-D walk's, never the test, so the verdicts
// are the same.
//
// Built only for shadows, in the sphere grid's frame; about one cell a
// sphere, and no smaller than twice a typical sphere's diameter (light/grid.h).
// Each entry carries its disc, so that a ray passing outside it (by
// more than the margin: the test could not have said otherwise) costs no
// read of the sphere. Memory: 20 bytes an entry and 4 bytes a cell: with
// about 2.25 entries a sphere in a packed box, some 50 bytes a sphere (and
// 9 a sphere while it is built: each entry's cell, light/key_sort.h).
#pragma once
#include <cstdint>
#include <vector>

#include "light/grid.h"
#include "memory/arrays.h"

namespace raycast {

class shadow_bins {
 public:
  shadow_bins() = default;
  // light: the unit direction toward the light, in the grid's frame (the
  // world's axes); built on `threads` threads (the same bins on any number).
  shadow_bins(const sphere_grid& grid, const float light[3], int threads = 1);

  // Where a shadow ray from p (grid frame) looks: the cell p projects to
  // (none: outside every disc), and p's coordinates across L and along it.
  struct query {
    size_t cell;
    float u, v, depth;
  };
  static constexpr size_t none = ~size_t(0);
  query locate(const float p[3]) const;
  // Prefetches what occluded(q) reads, in two steps over a batch's rays
  // (0: the cell's bounds, 1: the end of its list, where the scan starts),
  // so that their cache misses overlap instead of following one another.
  void prefetch(const query& q, int step) const;

  // Whether the ray from p along the light meets a sphere's ball but
  // sphere skip's (its index in the scene); q = locate(p).
  bool occluded(const query& q, const float p[3], uint32_t skip) const;
  bool occluded(const float p[3], uint32_t skip) const { return occluded(locate(p), p, skip); }

  size_t bytes() const { return first_.size() * 4 + entries_.size() * sizeof(entry); }
  size_t longest_list() const;  // the most entries a cell lists

  // A sphere's entry: public for the build's helpers.
  struct entry {
    float reach;  // C . L + r, plus the margin
    uint32_t k;     // the sphere's position in the grid (light/grid.h)
    float u, v, r;  // the disc: C's projection, and r plus the margin
  };
 private:
  entry entry_of(uint32_t p) const;  // the sphere at position p's
  void bin(const float hi[2]);

  const sphere_grid* grid_ = nullptr;
  float l_[3] = {0, 0, 0}, u_[3] = {0, 0, 0}, v_[3] = {0, 0, 0};  // L and the plane's axes
  float lo_[2] = {0, 0}, inv_g_ = 1;
  int dims_[2] = {0, 0};
  int threads_ = 1;
  out_of_order_array<uint32_t> first_;  // cells + 1
  filled_later_array<entry> entries_;
};

}  // namespace raycast
