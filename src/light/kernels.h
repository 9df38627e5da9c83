// The light's hot loops, compiled once an instruction set (light/lanes.h):
// the build's baseline (four lanes), AVX2 (eight) and AVX-512 (sixteen) on
// x86-64. Every compilation runs the same float operations lane by lane, so
// each gives every ray the same verdict: the width changes the speed alone.
// The width follows the CPU (RAYCAST_MAX_ISA caps it), not --backend: every
// backend's kernels hand their lit lanes to the same code.
#pragma once
#include <cstdint>
#include <vector>

#include "light/far/bvh.h"

namespace raycast {

// A near-field list (light/near/near_field.h): `count` spheres as blocks of
// sixteen, each block x[16] y[16] z[16] r[16] (grid frame), padded with NaN
// (no ray meets a NaN sphere).
struct sphere_blocks {
  const float* blocks = nullptr;
  uint32_t count = 0;
};

// A far-field query: the segment o + t d, t in [t0, tmax], blocked by a
// sphere but the one at position skip (light_kernels::far_occluded).
struct far_query {
  float o[3], d[3];
  float t0, tmax;
  uint32_t skip;
};

struct light_kernels {
  int width = 4;
  // Whether the segment o + t d, t in [t0, tmax] (d of unit length), meets
  // a sphere's ball other than the one at position skip (none: ~0u), where
  // o starts outside every ball but skip's and those of a near list that
  // covers t < t0 (where t0 is 0: the start inside a ball blocks too).
  bool (*far_occluded)(const bvh_view& v, const float o[3], const float d[3], float t0, float tmax, uint32_t skip);
  // far_occluded's verdicts for n queries (blocked[i]: 1 or 0), the rays
  // walking in turns, so that their reads overlap.
  void (*far_occluded_many)(const bvh_view& v, const far_query* q, uint32_t n, uint8_t* blocked);
  // far_occluded's verdicts for m <= 8 rays from one origin (bit r: ray r
  // blocked), walked together while they meet the same boxes.
  uint32_t (*far_occluded_one_origin)(const bvh_view& v, const float o[3], const float (*d)[3], uint32_t m,
                                      float t0, float tmax, uint32_t skip);
  // The spheres j but self (position) whose centre lies within reach + r_j
  // of c: their count (cap + 1: more than cap) and each one's x, y, z, r in
  // rows[0 .. 4) (each with room for cap + 8).
  uint32_t (*gather_ball)(const bvh_view& v, const float c[3], float reach, uint32_t self, float* const rows[4],
                          uint32_t cap);
  // ... of the spheres j but self within r + r_j (widened by `slack`) of
  // the ray from c along the unit l, none behind c by more than r_j + slack,
  // and each one's distance along l from c.
  uint32_t (*gather_capsule)(const bvh_view& v, const float c[3], float r, const float l[3], float slack,
                             uint32_t self, float* const rows[4], float* along, uint32_t cap);
  // Whether the segment o + t d, t in [0, tmax], meets a ball of the list.
  bool (*list_blocks)(const sphere_blocks& list, const float o[3], const float d[3], float tmax);
  // A hit's m <= 8 AO rays from o (on its sphere, normal n, rays into the
  // hemisphere about n) against its sphere's list: bit a set where ray a
  // meets a ball of the list within tmax. The list is first cut to the
  // spheres that reach above o's tangent plane within `within` of o.
  uint32_t (*list_ao)(const sphere_blocks& list, const float o[3], const float n[3], const float (*d)[3], int m,
                      float tmax, float within);
};

// The kernels of one width (4, 8 or 16; 0: the widest this CPU runs).
const light_kernels& light_kernels_for(int width = 0);
// The widths this build has and this CPU runs, narrowest first.
const std::vector<int>& light_widths();

// Each compilation's table (light/kernels_impl.cpp).
light_kernels kernels_w4();
light_kernels kernels_w8();
light_kernels kernels_w16();

}  // namespace raycast
