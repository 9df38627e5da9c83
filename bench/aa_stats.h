// The arithmetic of the antialiasing summary, free of the bench's machinery
// (tests/test_aa_bench.cpp checks it): an image's error against a converged
// reference, the log-log slope of error against samples, and the sample
// count at which a sampler's error curve reaches a given error.
#pragma once
#include <cstddef>
#include <optional>
#include <vector>

namespace raycast::bench {

struct image_error {
  double rmse = 0;     // over every pixel and channel
  double max_abs = 0;  // NaN counts as infinite
};
// Linear float colour (interleaved RGB) against the reference's doubles, same layout.
image_error measure_image_error(const float* image, const std::vector<double>& reference);

// One point of an error curve: samples per pixel and the RMSE there.
struct error_point {
  double samples = 0, rmse = 0;
};

// Least-squares slope of log(rmse) against log(samples) over the points with
// samples >= min_samples; nullopt with fewer than two such points or any
// RMSE not positive.
std::optional<double> loglog_slope(const std::vector<error_point>& curve, double min_samples = 4);

// The sample count N* at which the curve's RMSE equals `target`, interpolated
// linearly in log-log between the two points that bracket it (the curve
// sorted by samples; RMSE decreasing). Beyond the curve's last point it
// extrapolates with the slope over samples >= min_samples (extrapolated set);
// nullopt where the curve cannot say (target above its first point, or no
// falling slope to extrapolate with).
struct samples_match {
  double samples = 0;
  bool extrapolated = false;
};
std::optional<samples_match> samples_to_match(const std::vector<error_point>& curve, double target,
                                              double min_samples = 4);

}  // namespace raycast::bench
