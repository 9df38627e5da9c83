// The command line's particle files: --scene FILE.ply renders the bytes of
// the JSON scene of the same spheres; --radius, --color-by and their
// refusals; a hostile file is one line naming the file, the part and the
// byte, exit 2, nothing written; and what a sphere costs in memory, from
// --stats' peak.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "particles.h"

namespace {

using namespace raycast_test;

class CliPly : public ::testing::Test {
 protected:
  cli_sandbox box;
  const std::vector<std::string> camera = {"--lookfrom", "0.5,1,3", "--lookat", "0,0,-5", "--vfov", "40",
                                           "-w", "160", "--height", "90"};

  run_result run_with(std::vector<std::string> args) const {
    args.insert(args.end(), camera.begin(), camera.end());
    return box.run(args);
  }
};

using raycast_test::contains;

TEST_F(CliPly, APlyFileRendersItsJsonScenesBytes) {
  const std::vector<particle> ps = random_particles(2000, 21);
  write_file(box.work() / "p.json", json_of(ps));
  write_file(box.work() / "p.ply", ply_of(ps, enc::big));
  write_file(box.work() / "a.ply", ply_of(ps, enc::ascii));
  ASSERT_EQ(run_with({"--scene", box.path("p.json"), "-o", box.path("json.ppm")}).exit_code, 0);
  for (const char* name : {"p.ply", "a.ply"}) {
    const run_result r = run_with({"--scene", box.path(name), "-o", box.path("ply.ppm")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file(box.work() / "ply.ppm"), read_file(box.work() / "json.ppm")) << name;
  }
}

TEST_F(CliPly, RadiusAndColorByShapeAFileWithoutEither) {
  const std::vector<particle> ps = random_particles(500, 22);
  write_file(box.work() / "p.ply", ply_of(ps, enc::little, false, false));
  run_result r = run_with({"--scene", box.path("p.ply"), "-o", box.path("a.ppm")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--scene: " + box.path("p.ply") + ": the file gives no radius and no types: give --radius R"))
      << r.err;
  r = run_with({"--scene", box.path("p.ply"), "--radius", "0.2", "-o", box.path("normal.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_with({"--scene", box.path("p.ply"), "--radius", "0.2", "--color-by", "id", "--colormap", "magma",
                "--color-range", "0,250", "-o", box.path("magma.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ppm normal = parse_ppm(read_file(box.work() / "normal.ppm")), magma = parse_ppm(read_file(box.work() / "magma.ppm"));
  EXPECT_EQ(normal.width, 160);
  EXPECT_NE(normal.pixels, magma.pixels);
}

TEST_F(CliPly, ParticleOptionsAreRefusedWhereTheyMeanNothing) {
  write_file(box.work() / "p.ply", ply_of(random_particles(10, 23), enc::little));
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--scene", "world", "--color-by", "id"}, "--color-by: applies to particle files only"},
      {{"--color-by", "id"}, "--color-by: applies to particle files only"},
      {{"--scene", "world", "--view", "x"}, "--view: applies to particle files only"},
      {{"--scene", box.path("p.ply"), "--colormap", "gray"}, "--colormap: needs --color-by COLUMN"},
      {{"--scene", box.path("p.ply"), "--color-by", "id", "--color-range", "5,1"},
       "--color-range: '5' is not below '1' (want lo,hi with lo < hi)"},
      {{"--scene", box.path("p.ply"), "--radius", "-1"}, "--radius: '-1' is too small (above 0)"},
      {{"--scene", box.path("p.ply"), "--color-by", "idd"},
       "--color-by: 'idd' is not a column of this frame (it has: type, element, x, y, z, radius, id); did you mean id?"},
  };
  for (const auto& [args, message] : cases) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", box.path("out.ppm")});
    const run_result r = box.run(a);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, message)) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
}

// A hostile file: one line naming the file, the part and the byte; exit 2;
// the image it would have replaced is untouched and no temporary is left.
TEST_F(CliPly, AHostileFileIsOneLineAndNothingIsWritten) {
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\n"
                           "property float y\nproperty float z\nproperty float radius\nend_header\n";
  const std::pair<std::string, std::string> files[] = {
      {head + std::string(40, '\0'), "bad.ply: vertex: the header promises 100 vertices of 16 bytes"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty list uchar int y\nend_header\n",
       "bad.ply: vertex.y: a list property"},
      {"ply\nformat ascii 1.0\n" + std::string(3 << 20, ' '), "bad.ply: header: has no end_header in its first"},
  };
  for (const auto& [bytes, message] : files) {
    write_file(box.work() / "bad.ply", bytes);
    write_file(box.work() / "out.png", precious);
    const run_result r = box.run({"--scene", box.path("bad.ply"), "-o", box.path("out.png")});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(r.err.starts_with("raycast: error: --scene: " + box.path("bad.ply") + ": ")) << r.err;
    EXPECT_TRUE(contains(r.err, message)) << r.err;
    EXPECT_TRUE(contains(r.err, "(at byte ")) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_EQ(read_file(box.work() / "out.png"), precious);
  }
  const run_result r = box.run({"--scene", box.path("missing.ply"), "-o", box.path("out.png")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "missing.ply: No such file or directory")) << r.err;
}

// --stats' "peak RSS  N MB" in megabytes.
double peak_mb(const std::string& err) {
  const size_t at = err.find("peak RSS");
  return at == std::string::npos ? -1.0 : std::stod(err.substr(at + 8));
}

// What a sphere costs, file to image, as src/scene/README.md states it: the
// file's row, the colours --color-by makes, the float scene and primary
// index, and each secondary structure, from --stats' peak on a packed box
// of 300,000 spheres (a margin of about a sixth over what was measured).
TEST_F(CliPly, ASphereCostsWhatTheSceneRoomSays) {
  if (sanitized() || emulated()) GTEST_SKIP() << "the peak of a sanitized or emulated raycast is not its own";
  constexpr size_t n = 300000;
  const float side = float(std::cbrt(double(n) * 4.18879 / 0.3));  // radius 1, packing fraction 0.3
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> pos(0.0f, side);
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                    "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (size_t k = 0; k < 3 * n; ++k) put(ply, pos(rng), false);
  write_file(box.work() / "box.ply", ply);
  const std::string from = std::to_string(3 * side) + "," + std::to_string(2.4 * side) + "," + std::to_string(3.4 * side);
  const std::string at = std::to_string(side / 2) + "," + std::to_string(side / 2) + "," + std::to_string(side / 2);
  const auto peak = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"--scene", box.path("box.ply"), "--radius", "1", "--lookfrom", from, "--lookat", at,
                                     "--vfov", "30", "-w", "320", "--stats", "-o", box.path("box.ppm")};
    args.insert(args.end(), extra.begin(), extra.end());
    const run_result r = box.run(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return peak_mb(r.err);
  };
  const run_result sky = box.run({"-w", "320", "--stats", "-o", box.path("sky.ppm")});
  const double base = peak_mb(sky.err), per_mb = double(n) / 1e6;
  const double row = 12, colors = 12 + 8, primary = 100, shadows = 80, ao = 45;
  EXPECT_LT(peak({}), base + per_mb * (row + primary));
  EXPECT_LT(peak({"--color-by", "x"}), base + per_mb * (row + colors + primary));
  const std::vector<std::string> lit = {"--color-by", "x", "--light", "1,2,3"};
  std::vector<std::string> with = lit;
  with.push_back("--shadows");
  EXPECT_LT(peak(with), base + per_mb * (row + colors + primary + shadows));
  with.insert(with.end(), {"--ao", "4", "--ao-distance", "5"});
  EXPECT_LT(peak(with), base + per_mb * (row + colors + primary + shadows + ao));
}

}  // namespace
