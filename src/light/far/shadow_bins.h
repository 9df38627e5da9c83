// Light-space bins: the shadow rays of open scenes (clouds), where a sphere's
// shadow list would run through the whole scene and cost a walk of it to
// gather. A directional light's shadow rays are parallel, so the spheres are
// binned once in the light's own orthographic view (the "irregular
// z-buffer" of Johnson et al. and Wyman et al.): a 2-D grid over the plane
// across L, each sphere listed in every cell its disc (widened by 2^-20 of
// the grid) overlaps, each cell's list sorted by how far along L the sphere
// reaches, C . L + r. A shadow ray from P looks up the one cell P projects to
// and tests its spheres from the far end of the list down with the light's
// one test (light/blocks.h), stopping at the first that blocks or that ends
// before P (C . L + r < P . L: it and the rest lie wholly behind it). Only
// the candidates differ from a shadow list's, never the test, so the
// verdicts are the same.
//
// Over the far field's spheres (light/far/bvh.h), in its frame; cells twice
// a typical sphere's diameter. Each entry carries its disc, so that a ray
// passing outside it (by more than the margin: the test could not have said
// otherwise) costs no read of the sphere: its centre, and its radius as one
// of 256 classes (the largest radius times 2^(-c/16), the smallest class at
// least the sphere's own, so a disc is at most 4.4 % wider than the
// sphere's, and a scene of one radius has its own) in the low byte of the
// reach, which is rounded up to free it. Memory: 16 bytes an entry and 4
// bytes a cell, some 2.25 entries a sphere: about 40 bytes a sphere (while
// it is built, a band of entries more a thread, light/far/key_sort.h).
#pragma once
#include <cstdint>
#include <vector>

#include "light/far/bvh.h"
#include "memory/arrays.h"

namespace raycast {

class shadow_bins {
 public:
  shadow_bins() = default;
  // light: the unit direction toward the light, in the far field's frame
  // (the world's axes); built on `threads` threads (the same bins on any
  // number).
  shadow_bins(const sphere_bvh& spheres, const float light[3], int threads = 1);

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

  // Whether the ray from p along the light meets a sphere's ball but the
  // one at position skip's; q = locate(p).
  bool occluded(const query& q, const float p[3], uint32_t skip) const;
  bool occluded(const float p[3], uint32_t skip) const { return occluded(locate(p), p, skip); }

  size_t bytes() const { return first_.size() * 4 + entries_.size() * sizeof(entry); }
  size_t longest_list() const;  // the most entries a cell lists

  // A sphere's entry: public for the build's helpers.
  struct entry {
    // C . L + r plus the margin and reach_offset (so positive), rounded up to
    // a multiple of 256 ulps; its low byte holds the disc's radius class.
    float reach;
    uint32_t k;  // the sphere's position (light/far/bvh.h)
    float u, v;  // the disc's centre: C's projection
  };
  static constexpr float reach_offset = 4.0f;  // above any C . L in the frame's [-1, 1]^3
  float radius(const entry& e) const;          // the disc's: its class's, at least r plus the margin
 private:
  entry entry_of(uint32_t p) const;  // the sphere at position p's
  uint32_t radius_class(float r) const;
  void bin(const float hi[2]);

  const sphere_bvh* spheres_ = nullptr;
  float l_[3] = {0, 0, 0}, u_[3] = {0, 0, 0}, v_[3] = {0, 0, 0};  // L and the plane's axes
  float lo_[2] = {0, 0}, inv_g_ = 1;
  int dims_[2] = {0, 0};
  int threads_ = 1;
  float disc_[256] = {};  // each radius class's disc radius, widest first
  out_of_order_array<uint32_t> first_;  // cells + 1
  filled_later_array<entry> entries_;
};

}  // namespace raycast
