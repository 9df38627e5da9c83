// The far field's nodes over spheres sorted by their centres' Morton codes:
// an octree whose node over a range of codes that agree above some level
// splits it by the next three bits, up to eight children (the levels every
// code of a range shares are skipped, so no node has one child); a range of
// up to eight spheres is a leaf, and one whose codes are all equal is cut
// into eight runs. Each child's box is its spheres' (widened by 2^-16), not
// its octant's. Nodes are stored depth first; ranges of up to 2^15 under
// a bigger one are built by the preparation's threads in one loop and joined
// in depth-first order, so the nodes are the same on any number of threads.
#pragma once
#include <cstdint>

#include "light/far/bvh.h"

namespace raycast {

struct octree_input {
  const uint64_t* keys;  // by position: Morton code << 32 | scene index, ascending
  const float* xyzr;     // by position
  uint32_t n;
};

struct octree_result {
  out_of_order_array<bvh_node> nodes;
  uint32_t root = bvh_ref::empty;
  size_t leaves = 0;
  double leaf_volume = 0;  // the leaves' boxes' summed volume, in the nodes' order
};

octree_result build_octree(const octree_input& in, int threads);

// The widening of every box, in grid units: far above a box test's rounding
// (light/far/occlude.inl).
inline constexpr float box_margin = 0x1p-16f;

}  // namespace raycast
