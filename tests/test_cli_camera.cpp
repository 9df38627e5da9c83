// The positionable camera's options on the command line: refused cameras exit
// 2 with one line naming the option, and the lesson's camera is unchanged when
// none of them is given.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::run_result;

struct refused {
  const char* name;
  std::vector<std::string> args;
  const char* mentions;
};

class CliCameraRefused : public ::testing::TestWithParam<refused> {
 protected:
  cli_sandbox box;
};

TEST_P(CliCameraRefused, ExitsTwoWithOneLineAndWritesNothing) {
  std::vector<std::string> args = GetParam().args;
  args.insert(args.end(), {"-o", box.path("out.png")});
  const run_result r = box.run(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("raycast: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "want one line: " << r.err;
  EXPECT_NE(r.err.find(GetParam().mentions), std::string::npos) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

const refused refused_cases[] = {
    {"lookfrom_is_lookat", {"--lookfrom", "1,2,3", "--lookat", "1,2,3"}, "--lookat"},
    {"origin_is_lookat", {"--lookat", "0,0,0"}, "--lookat"},
    {"vup_parallel", {"--lookat", "0,5,0"}, "--vup"},
    {"vup_parallel_down", {"--lookat", "0,-1,0", "--vup", "0,3,0"}, "--vup"},
    {"vup_zero", {"--vup", "0,0,0"}, "--vup"},
    {"vup_along_default_view", {"--vup", "0,0,1"}, "--vup"},
    {"vfov_zero", {"--vfov", "0"}, "--vfov"},
    {"vfov_180", {"--vfov", "180"}, "--vfov"},
    {"vfov_negative", {"--vfov", "-30"}, "--vfov"},
    {"vfov_nan", {"--vfov", "nan"}, "--vfov"},
    {"vfov_text", {"--vfov", "wide"}, "--vfov"},
    {"vfov_and_viewport", {"--vfov", "90", "--viewport-height", "2"}, "--vfov"},
    {"origin_and_lookfrom", {"--origin", "0,0,0", "--lookfrom", "0,0,0"}, "--lookfrom"},
    {"lookat_two_numbers", {"--lookat", "1,2"}, "--lookat"},
    {"lookat_infinite", {"--lookat", "1,inf,2"}, "--lookat"},
    {"lookfrom_garbage", {"--lookfrom", "1,2,3x"}, "--lookfrom"},
    {"vup_repeated", {"--vup", "0,1,0", "--vup", "1,0,0"}, "--vup"},
    // An orthographic camera's rays are parallel: a field of view or a focal
    // length means nothing, and the refusal names both options.
    {"orthographic_vfov", {"--projection", "orthographic", "--vfov", "30"}, "--vfov: means nothing with --projection orthographic"},
    {"orthographic_focal_length", {"--focal-length", "2", "--projection", "orthographic"},
     "--focal-length: means nothing with --projection orthographic"},
    {"projection_unknown", {"--projection", "fisheye"}, "not one of perspective, orthographic"},
    // The light: shadows need a directional light; a direction is not zero.
    {"shadows_without_light", {"--scene", "lit-world", "--shadows"}, "--shadows: needs a directional light"},
    {"light_zero", {"--scene", "lit-world", "--light", "0,0,0"}, "--light: must not be 0,0,0"},
    {"light_two_numbers", {"--light", "1,2"}, "--light"},
    {"ao_negative", {"--ao", "-1"}, "--ao: '-1' is too small (at least 0)"},
    {"ao_too_many", {"--ao", "4097"}, "--ao: '4097' is too large (at most 4096)"},
    {"ao_distance_zero", {"--ao-distance", "0"}, "--ao-distance: '0' is too small (above 0)"},
};

INSTANTIATE_TEST_SUITE_P(Options, CliCameraRefused, ::testing::ValuesIn(refused_cases),
                         [](const ::testing::TestParamInfo<refused>& i) { return i.param.name; });

TEST(CliCamera, TheLessonsViewSpelledOutIsTheLessonsImage) {
  cli_sandbox box;
  ASSERT_EQ(box.run({"-o", "plain.ppm"}).exit_code, 0);
  ASSERT_EQ(box.run({"--lookfrom", "0,0,0", "--lookat", "0,0,-1", "--vup", "0,1,0", "-o", "spelled.ppm"})
                .exit_code,
            0);
  EXPECT_EQ(raycast_test::read_file(box.work() / "plain.ppm"),
            raycast_test::read_file(box.work() / "spelled.ppm"));
}

TEST(CliCamera, ATiltedCameraRendersSomethingElse) {
  cli_sandbox box;
  ASSERT_EQ(box.run({"-o", "plain.ppm"}).exit_code, 0);
  const run_result r = box.run({"--vup", "0.3,1,0", "--vfov", "90", "-o", "tilted.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(raycast_test::read_file(box.work() / "plain.ppm"),
            raycast_test::read_file(box.work() / "tilted.ppm"));
}

// The orthographic camera from the command line and from a scene file is the
// same picture, and another than the perspective one.
TEST(CliCamera, OrthographicFromTheOptionOrTheSceneFile) {
  cli_sandbox box;
  ASSERT_EQ(box.run({"--scene", "world", "-w", "160", "-o", "perspective.ppm"}).exit_code, 0);
  const run_result r =
      box.run({"--scene", "world", "-w", "160", "--projection", "orthographic", "--viewport-height", "3", "-o", "option.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  raycast_test::write_file(box.work() / "ortho.json",
                           "{\"camera\": {\"width\": 160, \"projection\": \"orthographic\", \"viewport_height\": 3},"
                           " \"spheres\": [{\"center\": [0, 0, -1], \"radius\": 0.5},"
                           " {\"center\": [0, -100.5, -1], \"radius\": 100}]}");
  ASSERT_EQ(box.run({"--scene", "ortho.json", "-o", "file.ppm"}).exit_code, 0);
  EXPECT_EQ(raycast_test::read_file(box.work() / "option.ppm"), raycast_test::read_file(box.work() / "file.ppm"));
  EXPECT_NE(raycast_test::read_file(box.work() / "option.ppm"), raycast_test::read_file(box.work() / "perspective.ppm"));
}

// The light from the command line and from a scene file's light and
// ambient_occlusion keys is the same picture; without them, today's.
TEST(CliCamera, TheLightFromTheOptionsOrTheSceneFile) {
  cli_sandbox box;
  ASSERT_EQ(box.run({"--scene", "lit-world", "-w", "160", "-o", "headlight.ppm"}).exit_code, 0);
  const run_result r = box.run({"--scene", "lit-world", "-w", "160", "--light", "1,1,0.5", "--shadows", "--ao", "4",
                                "--ao-distance", "2", "-o", "option.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  raycast_test::write_file(box.work() / "lit.json",
                           "{\"camera\": {\"width\": 160},"
                           " \"light\": {\"direction\": [1, 1, 0.5], \"shadows\": true},"
                           " \"ambient_occlusion\": {\"samples\": 4, \"distance\": 2},"
                           " \"spheres\": [{\"center\": [0, 0, -1], \"radius\": 0.5, \"shade\": \"lit\", \"color\": [1.0, 0.55, 0.1]},"
                           " {\"center\": [0, -100.5, -1], \"radius\": 100, \"shade\": \"lit\", \"color\": [0.7, 0.7, 0.7]}]}");
  const run_result f = box.run({"--scene", "lit.json", "-o", "file.ppm"});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  EXPECT_EQ(raycast_test::read_file(box.work() / "option.ppm"), raycast_test::read_file(box.work() / "file.ppm"));
  EXPECT_NE(raycast_test::read_file(box.work() / "option.ppm"), raycast_test::read_file(box.work() / "headlight.ppm"));
  raycast_test::write_file(box.work() / "bad.json", "{\"light\": {\"shadows\": 1}}");
  const run_result bad = box.run({"--scene", "bad.json", "-o", "bad.ppm"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("light.shadows: must be true or false"), std::string::npos) << bad.err;
}

}  // namespace
