// The near field: for each sphere the camera sees, the spheres that can
// block its hits' secondary rays nearby, gathered from the far field
// (light/far/bvh.h) when a ray of one of its pixels first asks, and kept
// where the rays of its other pixels find them. A hit's rays start on its
// sphere S (centre C, radius r), so
//   - the ball list holds every sphere j but S whose centre lies within
//     r + reach + r_j of C: all that can meet a ray of S within `reach`
//     (the AO rays; a hit's are tested against those that reach above its
//     tangent plane, light/near/list_rays.inl);
//   - the shadow list holds every sphere j but S within r + r_j of the line
//     from C along the light and not behind C, in order along it: all that
//     can meet a shadow ray of S at any distance.
// Each list is exact, as the far field's query is (the same test of every
// candidate, light/lanes.h): a ray's verdict is an OR over the spheres it
// meets, found in whichever list or structure holds them, so where a list
// was gathered (and how often) changes no verdict.
//
// Where they are kept: each render thread's ring of up to 2 MiB, the lists
// written one after another, the oldest overwritten, and a table of 4096
// spheres (by position) saying where each one's are. A row of pixels meets a few
// hundred spheres and the next row the same ones, so a sphere's lists are
// gathered about once a frame for each thread that renders its rows, and
// read from the caches: no memory grows with the scene or the picture.
// Each sphere listed takes 16 bytes (its x, y, z, r, as blocks of sixteen,
// one row a coordinate). Lists of more than most_listed spheres are not
// kept: their rays ask the far field from their start.
#pragma once
#include <atomic>
#include <cstdint>

#include "light/far/bvh.h"
#include "light/kernels.h"

namespace raycast {

struct near_settings {
  float reach = 0;             // grid units: the ball lists' distance (0: no ball lists)
  bool shadows = false;        // shadow lists along `light`
  float light[3] = {0, 0, 0};  // unit, toward the light, grid frame
};

// The near field for a render's rays: ball lists where AO rays are cast,
// reaching the whole AO distance where that holds a few hundred spheres on
// average (the far field then has no part in AO), else some 64; shadow lists
// where shadow rays are. ao_distance in grid units (infinity: unbounded).
near_settings near_settings_for(const sphere_bvh& bvh, bool shadows, const float light[3], bool ao, float ao_distance);

// A sphere's lists; `whole` false: the list was too long to keep.
struct near_lists {
  sphere_blocks ball, shadow;
  bool ball_whole = false, shadow_whole = false;
};

class near_field {
 public:
  static constexpr uint32_t most_listed = 1024;

  near_field(const sphere_bvh& bvh, const near_settings& s, const light_kernels& k);
  near_field(const near_field&) = delete;
  near_field& operator=(const near_field&) = delete;

  // The lists of the sphere at position p, gathered where this thread has
  // not kept them. Valid until this thread's next call.
  near_lists of(uint32_t p) const;

  const near_settings& settings() const { return settings_; }
  size_t lists() const { return lists_.load(std::memory_order_relaxed); }  // gathered so far, every thread
  // Seconds gathering them, summed over the threads.
  double seconds() const { return double(nanoseconds_.load(std::memory_order_relaxed)) * 1e-9; }
  // The threads' rings (up to ring_bytes each) and tables.
  static constexpr size_t ring_bytes = size_t(2) << 20, table_entries = 4096;
  size_t bytes() const { return bytes_.load(std::memory_order_relaxed); }

 private:
  struct cache;
  float* gather(uint32_t p, cache& c, uint64_t& at) const;

  const sphere_bvh& bvh_;
  const bvh_view view_;
  const near_settings settings_;
  const light_kernels& k_;
  const uint64_t id_;  // this field's, for the threads' caches
  mutable std::atomic<size_t> lists_{0}, bytes_{0};
  mutable std::atomic<uint64_t> nanoseconds_{0};
};

}  // namespace raycast
