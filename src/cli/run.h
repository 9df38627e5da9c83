// A parsed run (cli/options.h), rendered: each of its frames described
// (the next read ahead while one renders), prepared as a job of the library
// and written to its image or added to the movie; with the progress a person
// at a terminal sees and --stats' timings of every stage.
#pragma once
#include <cstdint>

#include "options.h"
#include "raycast/raycast.h"

namespace raycast::cli {

// What --stats reports: each stage's seconds, summed over the frames, which
// add up to the run's.
struct run_stats {
  double load = 0;     // reading the scene file or the frames
  double prepare = 0;  // the jobs: the float scene, culling, the light's structures
  api::job::timings output;
  api::job::stats job;  // the last frame's
  uint64_t rays = 0;    // pixels x samples
  size_t frames = 0;    // rendered (those --skip-existing found are not)
};

// Throws refusal (a frame that cannot be read), api::error, io::io_error.
void run(job& j, run_stats& st);

// --stats' block on standard error; total: the run's seconds.
void print_stats(const run_stats& st, double total);

}  // namespace raycast::cli
