#include "aa_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raycast::bench {

image_error measure_image_error(const float* image, const std::vector<double>& reference) {
  image_error e;
  double sum_sq = 0;
  for (size_t k = 0; k < reference.size(); ++k) {
    const double d = std::abs(double(image[k]) - reference[k]);
    sum_sq += d * d;
    if (!(d <= e.max_abs)) e.max_abs = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
  }
  e.rmse = reference.empty() ? 0 : std::sqrt(sum_sq / double(reference.size()));
  return e;
}

std::optional<double> loglog_slope(const std::vector<error_point>& curve, double min_samples) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const error_point& p : curve) {
    if (p.samples < min_samples) continue;
    if (!(p.rmse > 0) || !(p.samples > 0)) return std::nullopt;
    const double x = std::log(p.samples), y = std::log(p.rmse);
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || !(den > 0)) return std::nullopt;
  return (n * sxy - sx * sy) / den;
}

std::optional<samples_match> samples_to_match(const std::vector<error_point>& curve, double target,
                                              double min_samples) {
  if (curve.empty() || !(target > 0)) return std::nullopt;
  std::vector<error_point> c = curve;
  std::sort(c.begin(), c.end(),
            [](const error_point& a, const error_point& b) { return a.samples < b.samples; });
  if (std::any_of(c.begin(), c.end(), [](const error_point& p) { return !(p.rmse > 0); }))
    return std::nullopt;
  if (target > c.front().rmse) return std::nullopt;  // fewer samples than the curve has
  const double lt = std::log(target);
  for (size_t k = 0; k + 1 < c.size(); ++k) {
    const double y0 = std::log(c[k].rmse), y1 = std::log(c[k + 1].rmse);
    if (!(y1 <= lt && lt <= y0)) continue;
    const double x0 = std::log(c[k].samples), x1 = std::log(c[k + 1].samples);
    const double t = y0 == y1 ? 0 : (lt - y0) / (y1 - y0);
    return samples_match{std::exp(x0 + t * (x1 - x0)), false};
  }
  if (target == c.back().rmse) return samples_match{c.back().samples, false};
  const std::optional<double> slope = loglog_slope(c, min_samples);
  if (!slope || !(*slope < 0)) return std::nullopt;
  const error_point& last = c.back();
  return samples_match{last.samples * std::exp((lt - std::log(last.rmse)) / *slope), true};
}

}  // namespace raycast::bench
