// The antialiasing bench's arithmetic (bench/aa_stats.h) and its reference
// cache (bench/aa_reference.h): the slope and the samples-to-match
// interpolation on exact power laws, and a cached reference that reads back
// as written and is rebuilt when its header or scene no longer match.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "aa_reference.h"
#include "aa_stats.h"

namespace {

using namespace raycast::bench;

std::vector<error_point> power_law(double a, double slope, std::vector<double> ns) {
  std::vector<error_point> c;
  for (double n : ns) c.push_back({n, a * std::pow(n, slope)});
  return c;
}

TEST(AaStats, SlopeOfAPowerLawOverNAtLeastFour) {
  std::vector<error_point> c = power_law(0.1, -0.75, {4, 16, 64, 256});
  c.insert(c.begin(), error_point{1, 1.0});  // N = 1 is left out of the fit
  ASSERT_TRUE(loglog_slope(c).has_value());
  EXPECT_NEAR(*loglog_slope(c), -0.75, 1e-12);
  EXPECT_FALSE(loglog_slope(power_law(0.1, -0.5, {1, 4})).has_value());  // one point at N >= 4
}

TEST(AaStats, SamplesToMatchInterpolatesInLogLog) {
  const std::vector<error_point> c = power_law(0.1, -0.5, {1, 4, 16, 64, 256});
  const auto m = samples_to_match(c, 0.1 / std::sqrt(100.0));
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->samples, 100.0, 1e-9);
  EXPECT_FALSE(m->extrapolated);
  const auto far = samples_to_match(c, 0.1 / std::sqrt(1024.0));
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->samples, 1024.0, 1e-6);
  EXPECT_TRUE(far->extrapolated);
  EXPECT_FALSE(samples_to_match(c, 0.5).has_value());  // worse than one sample
}

TEST(AaStats, ImageErrorIsRmseAndMax) {
  const float img[4] = {1.0f, 2.0f, 3.0f, 4.0f};
  const image_error e = measure_image_error(img, {1.0, 2.0, 3.0, 6.0});
  EXPECT_DOUBLE_EQ(e.rmse, 1.0);
  EXPECT_DOUBLE_EQ(e.max_abs, 2.0);
}

TEST(AaReference, CacheRoundTripsAndRebuildsOnMismatch) {
  const std::string dir = ::testing::TempDir() + "aa-ref-test";
  std::filesystem::remove_all(dir);
  aa_reference_spec spec{"world", 16, 9, 16, raycast::sampler_kind::stratified, 7};
  const aa_reference built = cached_aa_reference(dir, spec);
  EXPECT_FALSE(built.from_cache);
  ASSERT_EQ(built.rgb.size(), size_t(16 * 9 * 3));
  ASSERT_EQ(built.file, aa_reference_file(dir, spec));
  const aa_reference read = cached_aa_reference(dir, spec);
  EXPECT_TRUE(read.from_cache);
  EXPECT_EQ(read.rgb, built.rgb);
  EXPECT_EQ(read.fingerprint, built.fingerprint);
  EXPECT_EQ(read.build_seconds, built.build_seconds);

  aa_reference_spec other = spec;
  other.seed = 8;  // same file name, another header
  EXPECT_FALSE(load_aa_reference(built.file, other).has_value());
  other = spec;
  other.scene = "normals";  // another scene under the world's file name
  EXPECT_FALSE(load_aa_reference(built.file, other).has_value());

  std::filesystem::resize_file(built.file, std::filesystem::file_size(built.file) - 8);  // torn
  EXPECT_FALSE(load_aa_reference(built.file, spec).has_value());
  const aa_reference again = cached_aa_reference(dir, spec);
  EXPECT_FALSE(again.from_cache);
  EXPECT_EQ(again.rgb, built.rgb);
  EXPECT_TRUE(load_aa_reference(built.file, spec).has_value());
  std::filesystem::remove_all(dir);
}

}  // namespace
