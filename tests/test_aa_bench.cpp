// The antialiasing bench's image error and its reference cache
// (bench/aa_reference.h): a cached reference that reads back as written and
// is rebuilt when its header or scene no longer match. (The summary's
// slope and samples-to-match arithmetic is bench/report.py's:
// tests/test_bench_report.py.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "aa_reference.h"

namespace {

using namespace raycast::bench;

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
