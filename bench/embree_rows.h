// raycast-bench's Embree peer and scaling section.
//
// Peer rows, one thread, 8-bit, every built-in scene with spheres:
//   render/embree16/float/SCENE/WxH/t1/rgb8   rtcIntersect16, 16 pixels a packet
//   render/embree1/float/SCENE/WxH/t1/rgb8    rtcIntersect1
// with the error counters of our rows (against the double reference, over the
// whole image; max_abs_err and rms_err from Embree's float colours).
//
// Scaling rows: N = 1, 4, 16, 64, 256, 1024, 4096 random small spheres in
// front of the lesson's camera (random_spheres; --quick: N = 1, 64, 1024 at
// 400x225), our best backend and rtcIntersect16, time only:
//   render/BACKEND/exact/random-N/WxH/t1/rgb8, render/embree16/float/random-N/WxH/t1/rgb8
#pragma once
#include <cstdint>
#include <iosfwd>
#include <utility>
#include <vector>

#include "report.h"
#include "scene/sphere.h"

namespace raycast::bench {

// n normal-shaded spheres, radius 0.05 ... 0.15, centres at depth 2 ... 8 and
// inside 90 % of the lesson camera's view there (viewport 2 high, 16:9, focal
// 1). Deterministic on every platform: std::mt19937 with a fixed seed (its
// output is specified by the standard) and explicit arithmetic on its words.
std::vector<sphere> random_spheres(int n);

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes, bool quick);

// Embree against our best backend and the book on `world` at w x h, one
// thread, 8-bit; then the scaling table and our growth from N = 16 to 1024.
void print_embree_summary(std::ostream& os, const run_table& table, int64_t w, int64_t h, bool quick);

}  // namespace raycast::bench
