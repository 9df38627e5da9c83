// raycast-bench's antialiasing rows: Monte Carlo error against run time.
//
//   aa/BACKEND/SAMPLER/SCENE/WxH/sN   ours: the best backend this CPU runs
//                                     (exact), SAMPLER random, stratified or
//                                     sobol, N samples a pixel, one thread,
//                                     rgb_f32 output, seed 0
//   aa/book7/world/WxH/s100           the book's ch. 7 program (bench/book_ch7.h)
//
// for SCENE world and sky, 400x225, N = 1, 4, 16, 64, 256 (--quick: 96x54,
// N = 1, 4, 16). N = 1 is the one-sample pixel point whatever the sampler:
// each sampler keeps its s1 row, the same image, so every curve starts there.
// Each row carries rms_err and max_abs_err of its linear colour against a
// converged reference (bench/aa_reference.h: stratified, 16384 samples a
// pixel; --quick: 4096), ns_per_px and ns_per_sample, and how the reference
// was had (ref_* counters).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "aa_reference.h"

namespace raycast::bench {

struct aa_config {
  int64_t width = 400, height = 225;
  std::vector<int64_t> samples = {1, 4, 16, 64, 256};
  std::vector<std::string> scenes = {"world", "sky"};
  std::vector<sampler_kind> samplers = {sampler_kind::random, sampler_kind::stratified, sampler_kind::sobol};
  int book_samples = 100;       // the book's row, on world
  uint32_t reference_samples = 16384;
  std::string reference_dir;    // where references are cached; empty: not cached
  std::string backend;          // the row names' BACKEND: best_backend()'s name
};
aa_config aa_config_for(bool quick, const std::string& reference_dir);

// The reference of a scene at the config's size (stratified, a fixed seed).
aa_reference_spec aa_reference_spec_for(const aa_config& cfg, const std::string& scene);

// The aa/ rows above, and the region rows (--region): a frame 4x their size
// at 16 samples, and its four quadrants, each its own row.
void register_aa_rows(const aa_config& cfg);

}  // namespace raycast::bench
