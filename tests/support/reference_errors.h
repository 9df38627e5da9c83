// Error against the double reference, measured one band of rows at a time so
// that no full-size extra image is needed: the one measurement behind the
// tests' bounds and the bench's error columns.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace raycast_test {

struct error_stats {
  double max_abs_err = 0;   // linear colour, float output (NaN counts as infinite)
  double sum_sq = 0;        // of the float errors, over every channel
  int max_lsb = 0;          // 8-bit output, largest |byte - reference byte|
  int64_t lsb_mismatches = 0;  // 8-bit channels that differ
  int64_t nan_count = 0;    // NaN channels in the float output
  int64_t channels = 0;     // compared so far
  // Where max_abs_err first occurs (output row, 0 = top; column; channel).
  int64_t worst_row = -1, worst_col = -1;
  int worst_channel = -1;

  double rms_err() const;
  double lsb_mismatch() const;  // as a fraction of the channels
  void merge(const error_stats& o);
  std::string where() const;  // "max difference X at row R, column C, channel K"
};

// The reference's colours and bytes for rows [r0, r1) of the scene's image
// (row 0 at the top), computed once and compared with any number of outputs.
class reference_band {
 public:
  reference_band(const raycast::scene& s, int64_t r0, int64_t r1);

  // Adds the errors of a path's output for these rows: interleaved RGB,
  // rows packed; either may be null (not compared).
  void compare(const float* out_f32, const unsigned char* out_rgb8, error_stats& acc) const;

 private:
  int64_t width_, r0_;
  std::vector<double> colour_;
  std::vector<unsigned char> bytes_;
};

}  // namespace raycast_test
