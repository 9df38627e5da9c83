// The converged picture the antialiasing rows are measured against: the
// double reference (raycast::reference_pixel_samples) averaged over a
// stratified sampler's many samples a pixel, computed once over all cores,
// row by row, and cached as a file so later runs only read it.
//
// File (native byte order; a cache, not an interchange format): the magic
// "RCAAREF1", then width, height (int64), samples, sampler (uint32), seed
// (uint64), the fingerprint (uint64), the scene's name (16 bytes, NUL
// padded), build seconds (double) and threads (uint32, then 4 bytes of
// padding), then width x height x 3 doubles, linear colour, rows top first.
// The fingerprint hashes the one-sample double picture and the first pixel's
// sample offsets, so a change of scene, camera, shading or sampler rebuilds
// the file even where its name and header fields are unchanged.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast::bench {

struct aa_reference_spec {
  std::string scene;  // the built-in scene's name
  int64_t width = 0, height = 0;
  uint32_t samples = 0;
  sampler_kind sampler = sampler_kind::stratified;
  uint64_t seed = 0;
};

struct aa_reference {
  aa_reference_spec spec;
  uint64_t fingerprint = 0;
  double build_seconds = 0;  // how long computing it took, when it was computed
  int threads = 0;           // on how many threads
  bool from_cache = false;   // read from `file` this time
  std::string file;          // empty: not cached
  std::vector<double> rgb;   // width x height x 3, rows top first
};

// The built-in scene `spec.scene` at the spec's size.
scene aa_scene(const aa_reference_spec& spec);

// Computes the reference (all cores, rows in parallel), timing it.
aa_reference compute_aa_reference(const aa_reference_spec& spec);

// dir/aa-ref-SCENE-WxH-SAMPLER-SAMPLES.bin.
std::string aa_reference_file(const std::string& dir, const aa_reference_spec& spec);

// The file's reference when its header matches the spec and the scene's
// fingerprint; nullopt when it is missing, short or mismatched.
std::optional<aa_reference> load_aa_reference(const std::string& file, const aa_reference_spec& spec);
// Writes it (through a temporary file renamed into place); false on failure.
bool save_aa_reference(const std::string& file, const aa_reference& ref);

// Loaded from dir when the file there matches, else computed and saved
// (dir created when missing; empty dir: computed, not cached). A file that
// cannot be written is reported on stderr and the computed one returned.
aa_reference cached_aa_reference(const std::string& dir, const aa_reference_spec& spec);

// An image's error against the reference (tests/test_aa_bench.cpp checks it):
// linear float colour, interleaved RGB, against the reference's doubles in
// the same layout; RMSE over every pixel and channel, max_abs with NaN
// counted as infinite.
struct image_error {
  double rmse = 0, max_abs = 0;
};
image_error measure_image_error(const float* image, const std::vector<double>& reference);

}  // namespace raycast::bench
