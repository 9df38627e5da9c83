// raycast-bench's Embree peer rows.
//
// Peer rows, one thread, 8-bit, every built-in scene with spheres:
//   render/embree16/float/SCENE/WxH/t1/rgb8   rtcIntersect16, 16 pixels a packet
//   render/embree1/float/SCENE/WxH/t1/rgb8    rtcIntersect1
// with the error counters of our rows (against the double reference, over the
// whole image; max_abs_err and rms_err from Embree's float colours).
//
// The scale rows (particle clouds of up to 10^7 spheres, ours and Embree)
// are bench/scale_rows.h.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "errors.h"

namespace raycast::bench {

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes);

// Our fastest backend for spheres, the peers' yardstick: the last core path in
// available_paths()' order (sse2, avx2, avx512), exact (fast renders spheres
// as exact does).
const path& best_sphere_path();

}  // namespace raycast::bench
