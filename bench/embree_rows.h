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
#include <iosfwd>
#include <utility>
#include <vector>

#include "report.h"

namespace raycast::bench {

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes);

// Embree against our best backend and the book on `world` at w x h, one
// thread, 8-bit.
void print_embree_summary(std::ostream& os, const run_table& table, int64_t w, int64_t h);

}  // namespace raycast::bench
