// The `raycast` command line's settings: a scene file under the options that
// override it, and the errors that name an option or a file's key as typed
// (too small or too large, slips and their nearest names, unreadable files).
#include <gtest/gtest.h>


#include <ostream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::count_lines;
using raycast_test::parse_ppm;
using raycast_test::have_image_module;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;
using raycast_test::write_file;

namespace fs = std::filesystem;

using raycast_test::contains;
using raycast_test::expect_one_error_line;

class Cli : public ::testing::Test {
 protected:
  cli_sandbox box;
};


// Scene files: the file's settings, overridden by the options; errors name the
// file and the JSON path; a file that cannot be read is a usage error too.
TEST_F(Cli, SceneFileAndOptionsThatOverrideIt) {
  raycast_test::write_file(box.work() / "scene.json",
                           R"({"camera": {"width": 64, "vfov": 200},
                               "spheres": [{"center": [0, 0, -1], "radius": 0.5}]})");
  run_result r = box.run({"--scene", "scene.json", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--scene: scene.json: camera.vfov: ");
  r = box.run({"--scene", "scene.json", "--vfov", "90", "-w", "32", "-o", "a.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const raycast_test::ppm p = raycast_test::parse_ppm(raycast_test::read_file(box.work() / "a.ppm"));
  ASSERT_TRUE(p.error.empty()) << p.error;
  EXPECT_EQ(p.width, 32);
  EXPECT_EQ(p.height, 18);
  r = box.run({"--scene", "scene.json", "--viewport-height", "2", "-o", "b.ppm"});
  EXPECT_EQ(r.exit_code, 0) << r.err;  // --viewport-height replaces the file's vfov
}

// The command line overrides the file, key by key, and what is derived is
// derived from the merged settings.
TEST_F(Cli, AnOptionOverridesTheSameFileKey) {
  write_file(box.work() / "wide.json", R"({"camera": {"width": 64, "height": 10}})");
  ASSERT_EQ(box.run({"--scene", "wide.json", "--height", "20", "-o", "a.ppm"}).exit_code, 0);
  const raycast_test::ppm p = parse_ppm(read_file(box.work() / "a.ppm"));
  EXPECT_EQ(p.width, 64);
  EXPECT_EQ(p.height, 20);
}

TEST_F(Cli, TheHeightFollowsAWidthGivenOverTheFilesAspect) {
  write_file(box.work() / "square.json", R"({"camera": {"width": 64, "aspect": "2:1"}})");
  ASSERT_EQ(box.run({"--scene", "square.json", "-w", "40", "-o", "a.ppm"}).exit_code, 0);
  const raycast_test::ppm p = parse_ppm(read_file(box.work() / "a.ppm"));
  EXPECT_EQ(p.width, 40);
  EXPECT_EQ(p.height, 20);  // 40 / 2, not the file's 64 / 2
}

TEST_F(Cli, AFilesVupLooksDownFromTheLookfromTheOptionsGive) {
  // vup without lookat: the lesson's view down -z from the camera, wherever
  // --lookfrom puts it; the same image as giving that lookat outright.
  write_file(box.work() / "tilt.json", R"({"camera": {"width": 32, "vup": [0.3, 1, 0]}})");
  ASSERT_EQ(box.run({"--scene", "tilt.json", "--lookfrom", "5,0,0", "-o", "a.ppm"}).exit_code, 0);
  ASSERT_EQ(box.run({"-w", "32", "--vup", "0.3,1,0", "--lookfrom", "5,0,0", "--lookat", "5,0,-1", "-o", "b.ppm"})
                .exit_code,
            0);
  EXPECT_EQ(read_file(box.work() / "a.ppm"), read_file(box.work() / "b.ppm"));
}

TEST_F(Cli, AnAspectIsSpelledTheSameInTheFileAndOnTheCommandLine) {
  for (const std::string aspect : {"2:1", "2", "2.0", "4:2", "1e0:0.5"}) {
    write_file(box.work() / "a.json", R"({"camera": {"width": 32, "aspect": ")" + aspect + R"("}})");
    ASSERT_EQ(box.run({"--scene", "a.json", "-o", "file.ppm"}).exit_code, 0) << aspect;
    ASSERT_EQ(box.run({"-w", "32", "--aspect", aspect, "-o", "cli.ppm"}).exit_code, 0) << aspect;
    EXPECT_EQ(read_file(box.work() / "file.ppm"), read_file(box.work() / "cli.ppm")) << aspect;
    EXPECT_EQ(parse_ppm(read_file(box.work() / "cli.ppm")).height, 16) << aspect;
  }
  for (const std::string aspect : {"16:0", "wide", " 2:1", "-2:1"}) {
    write_file(box.work() / "a.json", R"({"camera": {"aspect": ")" + aspect + R"("}})");
    const run_result file = box.run({"--scene", "a.json", "-o", "file.ppm"});
    const run_result cli = box.run({"--aspect", aspect, "-o", "cli.ppm"});
    EXPECT_EQ(file.exit_code, 2) << aspect;
    EXPECT_EQ(cli.exit_code, 2) << aspect;
    // The same reason, after the file's path or the option.
    const std::string why = cli.err.substr(cli.err.find("--aspect: ") + 10);
    EXPECT_NE(file.err.find("camera.aspect: " + why.substr(0, why.size() - 1)), std::string::npos)
        << file.err << " vs " << cli.err;
  }
}

TEST_F(Cli, RangeErrorsSayTooSmallOrTooLargeWithTheTokenAsTyped) {
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--width", "0"}, "raycast: error: --width: '0' is too small (at least 1)\n"},
      {{"--width", "16777217"}, "raycast: error: --width: '16777217' is too large (at most 16777216)\n"},
      {{"--vfov", "180"}, "raycast: error: --vfov: '180' is too large (below 180)\n"},
      {{"--vfov", "-0"}, "raycast: error: --vfov: '-0' is too small (above 0)\n"},
      {{"--threads", "1025"}, "raycast: error: --threads: '1025' is too large (at most 1024)\n"},
      {{"--samples", "0"}, "raycast: error: --samples: '0' is too small (at least 1)\n"},
      {{"--sky-top", "1,1e31,1"}, "raycast: error: --sky-top: component 2: '1e31' is too large (at most 1e+30)\n"},
      {{"--width", std::string(100, '9')},
       "raycast: error: --width: '" + std::string(32, '9') + "\u2026' is too large (at most 16777216)\n"},
      {{"--seed", "-1"}, "raycast: error: --seed: '-1' is not a whole number from 0 to 18446744073709551615\n"},
      // Beyond a double both ways, in the row's terms: a tiny field of view is not an overflow.
      {{"--vfov", "1e-400"}, "raycast: error: --vfov: '1e-400' is too small (above 0)\n"},
      {{"--width", "-99999999999999999999"},
       "raycast: error: --width: '-99999999999999999999' is too small (at least 1)\n"},
      {{"--viewport-height", "1e400"},
       "raycast: error: --viewport-height: '1e400' is too large (beyond the largest double, 1.8e308)\n"},
      {{"--lookfrom", "1e400,0,0"},
       "raycast: error: --lookfrom: component 1: '1e400' is too large (beyond the largest double, 1.8e308)\n"},
      {{"--lookfrom", "1e-400,0,0"},
       "raycast: error: --lookfrom: component 1: '1e-400' is too near 0 (nearer than the smallest double, 4.9e-324)\n"},
      {{"--viewport-height", "1e-300", "--aspect", "1e-300"},
       "raycast: error: --viewport-height: viewport height is too small for this aspect ratio: the viewport width "
       "(aspect x viewport height) is below the smallest double\n"},
  };
  for (const auto& [args, want] : cases) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", "a.ppm"});
    const run_result r = box.run(a);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, want);
  }
  // An unknown option is quoted no longer either.
  const run_result bogus = box.run({"--" + std::string(1000, 'x'), "-o", "a.ppm"});
  EXPECT_EQ(bogus.exit_code, 2);
  EXPECT_EQ(bogus.err, "raycast: error: --" + std::string(30, 'x') + "\u2026: no such option (see --help)\n");
  write_file(box.work() / "w.json", "{\"camera\": {\"width\": 0}}");
  const run_result r = box.run({"--scene", "w.json", "-o", "a.ppm"});
  EXPECT_EQ(r.err, "raycast: error: --scene: w.json: camera.width: '0' is too small (at least 1) (at line 1, column 22: 0)\n");
  // Overridden, the file's value is no error.
  EXPECT_EQ(box.run({"--scene", "w.json", "-w", "8", "-o", "a.ppm"}).exit_code, 0);
}

// A slip (a letter swapped, dropped or added) gets the name it most likely
// meant; an argument no option takes is named as typed, first one first.
TEST_F(Cli, SlipsGetTheNearestNameAndNothingIsWritten) {
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--sampels", "4"}, "--sampels: no such option; did you mean --samples?"},
      {{"--sampels=4"}, "--sampels: no such option; did you mean --samples?"},
      {{"--widht", "8"}, "--widht: no such option; did you mean --width?"},
      {{"--orth"}, "--orth: no such option (see --help)"},
      {{"-x"}, "-x: no such option (see --help)"},
      {{"4"}, "'4': not expected (no option takes it: each takes one value; see --help)"},
      {{"--scene", "wrld"},
       "--scene: 'wrld' is not one of sky, red-sphere, normals, world, lit-world, a .json scene file or a particle file (LAMMPS dump, extended XYZ, GSD, PLY); did you "
       "mean world?"},
      {{"--backend", "avx"}, "--backend: 'avx' is not one of auto, reference, scalar, sse2, avx2, avx512, neon; did "
                             "you mean avx2?"},
      {{"--projection", "orth"},
       "--projection: 'orth' is not one of perspective, orthographic; did you mean orthographic?"},
      {{"--sampler", "Sobol"}, "--sampler: 'Sobol' is not one of random, stratified, sobol; did you mean sobol?"},
      {{"--format", "pgn"}, "--format: 'pgn' is not one of png, ppm, pnm, jpg, jpeg, tif, tiff, exr; did you mean "
                            "png?"},
      {{"-o", "b.ppm"}, "--output: given 2 times; give it once (see --help)"},
  };
  for (const auto& [args, want] : cases) {
    std::vector<std::string> a = {"-o", "a.ppm"};
    a.insert(a.end(), args.begin(), args.end());
    const run_result r = box.run(a);
    EXPECT_EQ(r.exit_code, 2) << want;
    EXPECT_EQ(r.err, "raycast: error: " + want + "\n");
    EXPECT_TRUE(box.entries().empty());
  }
  // A scene file's unknown key, too.
  raycast_test::write_file(box.work() / "k.json", R"({"spheres": [{"center": [0, 0, -1], "raduis": 1}]})");
  const run_result r = box.run({"--scene", "k.json", "-o", "a.ppm"});
  EXPECT_EQ(r.err, "raycast: error: --scene: k.json: spheres[0].raduis: unknown key (known here: center, radius, "
                   "shade, color); did you mean radius? (at line 1, column 37: \"raduis\")\n");
}

// 0 threads is all cores, as in Python and C++.
TEST_F(Cli, ZeroThreadsIsAllCores) {
  const run_result all = box.run({"--scene", "world", "-w", "64", "--threads", "0", "-o", "-"});
  const run_result one = box.run({"--scene", "world", "-w", "64", "--threads", "1", "-o", "-"});
  EXPECT_EQ(all.exit_code, 0) << all.err;
  EXPECT_EQ(all.out, one.out);
}

TEST_F(Cli, SceneFileErrorsNameTheJsonPath) {
  raycast_test::write_file(box.work() / "bad.json",
                           R"({"spheres": [{"center": [0, 0, -1], "radius": 1},
                                           {"center": [0, 0, -1], "radius": 1},
                                           {"center": [0, 0, -1], "radius": 1},
                                           {"center": [0, 0, -1], "radius": -1}]})");
  run_result r = box.run({"--scene", "bad.json", "-w", "16", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--scene: bad.json: spheres[3].radius: ");
  // A file that cannot be read is an I/O failure: exit 1.
  r = box.run({"--scene", "missing.json", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "--scene: missing.json: No such file or directory");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"bad.json"});
}

// Hostile scene paths: each one line, exit 1 (a file that cannot be read is
// an I/O failure), nothing written, and nothing that blocks (a FIFO with no
// writer) or reads without end.
TEST_F(Cli, SceneFilesThatAreNotRegularFilesAreRefused) {
  fs::create_directory(box.work() / "dir.json");
  ASSERT_EQ(mkfifo((box.work() / "fifo.json").c_str(), 0600), 0);
  const std::pair<std::string, std::string> cases[] = {
      {"dir.json", "--scene: dir.json: is a directory"},
      {"fifo.json", "--scene: fifo.json: is a FIFO"},
      {"/dev/null/x.json", "--scene: /dev/null/x.json: Not a directory"},
  };
  for (const auto& [name, want] : cases) {
    const run_result r = box.run({"--scene", name, "-o", "a.ppm"});
    EXPECT_EQ(r.exit_code, 1) << name;
    expect_one_error_line(r, want);
  }
  // /dev/zero never ends; it is refused as a device. Its name lacks ".json", so
  // reach it through a link that has it.
  fs::create_symlink("/dev/zero", box.work() / "zero.json");
  const run_result r = box.run({"--scene", "zero.json", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "--scene: zero.json: is a character device");
  EXPECT_EQ(box.entries(), (std::vector<std::string>{"dir.json", "fifo.json", "zero.json"}));
}

TEST_F(Cli, SceneFileSyntaxErrorsSayWhere) {
  write_file(box.work() / "dup.json", "{\"camera\": {\"width\": 64,\n  \"width\": 32}}");
  run_result r = box.run({"--scene", "dup.json", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--scene: dup.json: camera.width: duplicate key (at line 2, column 3: \"width\")");
  write_file(box.work() / "far.json", R"({"spheres": [{"center": [0, 0, -2e38], "radius": 1}]})");
  r = box.run({"--scene", "far.json", "-o", "a.ppm"});
  EXPECT_EQ(r.exit_code, 2);
  expect_one_error_line(r, "--scene: far.json: spheres[0].center: sphere centre must be within 1e37");
  EXPECT_EQ(box.entries(), (std::vector<std::string>{"dup.json", "far.json"}));
}


}  // namespace
