#include "reference_errors.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "reference/reference.h"

namespace raycast_test {

double error_stats::rms_err() const { return channels ? std::sqrt(sum_sq / double(channels)) : 0.0; }

double error_stats::lsb_mismatch() const {
  return channels ? double(lsb_mismatches) / double(channels) : 0.0;
}

void error_stats::merge(const error_stats& o) {
  if (o.max_abs_err > max_abs_err) {
    max_abs_err = o.max_abs_err;
    worst_row = o.worst_row;
    worst_col = o.worst_col;
    worst_channel = o.worst_channel;
  }
  sum_sq += o.sum_sq;
  max_lsb = std::max(max_lsb, o.max_lsb);
  lsb_mismatches += o.lsb_mismatches;
  nan_count += o.nan_count;
  channels += o.channels;
}

std::string error_stats::where() const {
  return "max difference " + std::to_string(max_abs_err) + " at row " + std::to_string(worst_row) +
         ", column " + std::to_string(worst_col) + ", channel " + std::to_string(worst_channel);
}

reference_band::reference_band(const raycast::scene& s, int64_t r0, int64_t r1)
    : width_(s.cam.image_width), r0_(r0) {
  const size_t n = size_t(width_ * (r1 - r0) * 3);
  colour_.resize(n);
  bytes_.resize(n);
  const int64_t H = s.cam.image_height;
  for (int64_t r = r0; r < r1; ++r)
    for (int64_t i = 0; i < width_; ++i) {
      const raycast::color c = raycast::reference_pixel(s, i, H - 1 - r);
      const size_t at = size_t(((r - r0) * width_ + i) * 3);
      for (int k = 0; k < 3; ++k) {
        colour_[at + size_t(k)] = c[k];
        bytes_[at + size_t(k)] = raycast::to_byte(c[k]);
      }
    }
}

void reference_band::compare(const float* out_f32, const unsigned char* out_rgb8,
                             error_stats& acc) const {
  const size_t n = colour_.size();
  acc.channels += int64_t(n);
  for (size_t k = 0; k < n; ++k) {
    if (out_f32) {
      double e = std::abs(double(out_f32[k]) - colour_[k]);
      if (!std::isfinite(out_f32[k])) e = std::numeric_limits<double>::infinity();
      if (std::isnan(out_f32[k])) ++acc.nan_count;
      if (e > acc.max_abs_err || (acc.worst_row < 0 && e == acc.max_abs_err)) {
        acc.max_abs_err = e;
        const int64_t px = int64_t(k / 3);
        acc.worst_row = r0_ + px / width_;
        acc.worst_col = px % width_;
        acc.worst_channel = int(k % 3);
      }
      acc.sum_sq += e * e;
    }
    if (out_rgb8) {
      const int lsb = std::abs(int(out_rgb8[k]) - int(bytes_[k]));
      acc.max_lsb = std::max(acc.max_lsb, lsb);
      acc.lsb_mismatches += lsb != 0;
    }
  }
}

}  // namespace raycast_test
