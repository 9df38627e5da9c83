// The environment raycast reads: SOURCE_DATE_EPOCH (the date EXR and TIFF
// record) and RAYCAST_MAX_ISA (the widest backend auto may pick); a malformed
// value is a usage error (exit 2, one line, nothing written).
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::how_it_ended;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;

using raycast_test::expect_success;
using raycast_test::expect_usage_error;

// SOURCE_DATE_EPOCH: the DateTime EXR and TIFF record, so two runs a second
// apart give the same bytes.
class SourceDateEpoch : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(SourceDateEpoch, TwoRunsGiveTheSameBytes) {
  const std::string format = GetParam();
  run_options opts;
  opts.env = {"SOURCE_DATE_EPOCH=1700000000"};
  expect_success(box.run({"-w", "64", "-o", "a." + format}, opts));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  expect_success(box.run({"-w", "64", "-o", "b." + format}, opts));
  const std::string a = read_file(box.work() / ("a." + format));
  EXPECT_EQ(a, read_file(box.work() / ("b." + format)));
  EXPECT_NE(a.find("2023:11:14 22:13:20"), std::string::npos) << "the date is not recorded";
}

INSTANTIATE_TEST_SUITE_P(Formats, SourceDateEpoch, ::testing::Values("exr", "tif"),
                         [](const auto& p) { return std::string(p.param); });

TEST(Environment, MalformedSourceDateEpochIsAUsageError) {
  cli_sandbox box;
  run_options opts;
  opts.env = {"SOURCE_DATE_EPOCH=yesterday"};
  expect_usage_error(box.run({"-o", "x.exr"}, opts),
                     "SOURCE_DATE_EPOCH: 'yesterday' is not a number of seconds since 1970-01-01 UTC "
                     "(0 to 253402300799)");
  EXPECT_TRUE(box.entries().empty());
}

TEST(Environment, BogusMaxIsaIsAUsageError) {
  cli_sandbox box;
  run_options opts;
  opts.env = {"RAYCAST_MAX_ISA=avx3"};
  expect_usage_error(box.run({"-o", "x.ppm"}, opts),
                     "RAYCAST_MAX_ISA: 'avx3' is not one of scalar, sse2, avx2, avx512, neon; did you mean avx2?");
  EXPECT_TRUE(box.entries().empty());
  // Before anything is printed: --version names the backend it would cap.
  opts.env = {"RAYCAST_MAX_ISA=foo"};
  const run_result r = box.run({"--version"}, opts);
  expect_usage_error(r, "RAYCAST_MAX_ISA: 'foo' is not one of scalar, sse2, avx2, avx512, neon");
  EXPECT_EQ(r.out, "");
}

TEST(Environment, EmptyMaxIsaMeansUnset) {
  cli_sandbox box;
  run_options opts;
  opts.env = {"RAYCAST_MAX_ISA="};
  expect_success(box.run({"-o", "x.ppm"}, opts));
}


}  // namespace
