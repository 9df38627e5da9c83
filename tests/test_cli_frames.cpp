// The command line over the simulation data real tools wrote (the fixture
// formats.files: LAMMPS's dumps, ASE's extended XYZ, gsd's GSD): the same
// frame from each format renders the same bytes; a trajectory renders every
// frame (or --frames) to a pattern's names or to a movie, framed by its first
// frame; several frames to one name, frames beyond the file and a frame cut
// short are refused in one line, every frame before it kept; --skip-existing
// renders only what is missing.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

using namespace raycast_test;

const fs::path files = RAYCAST_FORMATS_FILES;

using raycast_test::contains;

// Pixels that are not the sky's blue-white lerp: the particles in view.
size_t particle_pixels(const ppm& p) {
  size_t n = 0;
  for (size_t k = 0; k + 2 < p.pixels.size(); k += 3)
    if (uint8_t(p.pixels[k + 2]) != 255) ++n;
  return n;
}

class CliFrames : public ::testing::Test {
 protected:
  cli_sandbox box;
  std::string file(const char* name) const { return (files / name).string(); }
};

TEST_F(CliFrames, TheSameFrameFromEachFormatRendersTheSameBytes) {
  const char* names[] = {"same.lammpstrj", "same.lammpstrj.gz", "same.extxyz", "same.gsd"};
  std::string first;
  for (const char* name : names) {
    const run_result r = box.run({"--scene", file(name), "--radius", "0.2", "--shade", "normal", "-q", "-o", box.path("a.ppm")});
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const std::string bytes = read_file(box.work() / "a.ppm");
    if (first.empty()) first = bytes;
    EXPECT_EQ(bytes, first) << name << " renders other bytes than " << names[0];
  }
  EXPECT_GT(particle_pixels(parse_ppm(first)), 1000u);  // framed: the box is in view
}

TEST_F(CliFrames, ScaledAndUnscaledDumpsRenderTheSameFrames) {
  for (const char* frame : {"0", "-1"}) {
    ASSERT_EQ(box.run({"--scene", file("melt.atom"), "--frames", frame, "-q", "-o", box.path("scaled.ppm")}).exit_code, 0);
    ASSERT_EQ(box.run({"--scene", file("melt.dump"), "--frames", frame, "-q", "-o", box.path("plain.ppm")}).exit_code, 0);
    const ppm a = parse_ppm(read_file(box.work() / "scaled.ppm")), b = parse_ppm(read_file(box.work() / "plain.ppm"));
    ASSERT_EQ(a.error, "");
    // The scaled dump's positions are lo + xs (hi - lo): they round apart
    // from the printed x by an ulp, so a silhouette pixel may differ.
    size_t differ = 0;
    for (size_t k = 0; k < a.pixels.size(); ++k) differ += a.pixels[k] != b.pixels[k];
    EXPECT_LT(differ, a.pixels.size() / 200) << frame;
  }
}

TEST_F(CliFrames, EveryFrameGoesToItsPatternsName) {
  const run_result r = box.run({"--scene", file("melt.dump"), "-q", "--stats", "-o", box.path("f_%03d.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> want = {"f_000.ppm", "f_001.ppm", "f_002.ppm", "f_003.ppm", "f_004.ppm"};
  EXPECT_EQ(box.entries(), want);
  EXPECT_TRUE(contains(r.err, "  frames             5")) << r.err;
  // The atom count changes between frames, the camera (frame 0's) does not:
  // fewer atoms, fewer particle pixels, the same image size.
  const ppm f0 = parse_ppm(read_file(box.work() / "f_000.ppm")), f4 = parse_ppm(read_file(box.work() / "f_004.ppm"));
  EXPECT_EQ(f0.width, f4.width);
  EXPECT_GT(particle_pixels(f0), 0u);
  EXPECT_NE(f0.pixels, f4.pixels);
  // A slice, as Python's: the frames' indices in the file name them.
  ASSERT_EQ(box.run({"--scene", file("melt.dump"), "--frames", "::2", "-q", "-o", box.path("s%d.ppm")}).exit_code, 0);
  for (const char* n : {"s0.ppm", "s2.ppm", "s4.ppm"}) EXPECT_TRUE(fs::exists(box.work() / n)) << n;
  EXPECT_FALSE(fs::exists(box.work() / "s1.ppm"));
  // Frame 4 alone is the same picture as frame 4 of the run.
  ASSERT_EQ(box.run({"--scene", file("melt.dump"), "--frames", "4", "-q", "-o", box.path("alone.ppm")}).exit_code, 0);
  EXPECT_EQ(read_file(box.work() / "alone.ppm"), read_file(box.work() / "f_004.ppm"));
}

TEST_F(CliFrames, WhatCannotBeRenderedIsRefusedInOneLine) {
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"--scene", file("melt.dump"), "-o", box.path("one.ppm")},
       "--output: the file's frames to one file: give a pattern such as f_%05d.png"},
      {{"--scene", file("melt.dump"), "--frames", "1:3", "-o", box.path("two.ppm")}, "--output: 2 frames to one file"},
      {{"--scene", file("melt.dump"), "--frames", "5", "-o", box.path("x.ppm")},
       "--frames: 5 is beyond the file's 5 frames (0 to 4, or -5 to -1 from the end)"},
      {{"--scene", file("melt.dump"), "--frames", "3:1", "-o", box.path("x%d.ppm")},
       "--frames: selects none of the file's 5 frames"},
      {{"--scene", "world", "--frames", "0", "-o", box.path("x.ppm")}, "--frames: applies to a trajectory"},
      {{"--scene", file("melt.dump"), "-o", box.path("x%d%d.ppm")}, "has more than one %d"},
      {{"--scene", file("melt.dump"), "-o", box.path("x%s.ppm")}, "a frame's number is written %d or %05d"},
      {{"--scene", file("melt.dump"), "--color-by", "c_pee", "-o", box.path("x%d.ppm")},
       "--color-by: 'c_pee' is not a column of this frame"},
  };
  for (const auto& [args, message] : cases) {
    const run_result r = box.run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(contains(r.err, message)) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  }
  EXPECT_TRUE(box.entries().empty());
}

// A trajectory cut short inside its third frame: the first two are written,
// then one line names the file, the frame and the line; exit 2.
TEST_F(CliFrames, AFrameCutShortStopsTheRunAndKeepsEveryFrameBefore) {
  const std::string text = read_file(files / "melt.dump");
  size_t at = 0;
  for (int k = 0; k < 3; ++k) at = text.find("ITEM: TIMESTEP", at + 1);
  write_file(box.work() / "cut.dump", text.substr(0, at + (text.find("ITEM: ATOMS", at) - at) + 200));
  const run_result r = box.run({"--scene", box.path("cut.dump"), "-q", "-o", box.path("f%d.ppm")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "cut.dump: frame 3")) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  for (const char* n : {"f0.ppm", "f1.ppm", "f2.ppm"}) EXPECT_TRUE(fs::exists(box.work() / n)) << n;
  EXPECT_TRUE(box.leftovers().empty());
}

TEST_F(CliFrames, SkipExistingRendersOnlyTheFramesMissing) {
  ASSERT_EQ(box.run({"--scene", file("melt.dump"), "-q", "-o", box.path("f%d.ppm")}).exit_code, 0);
  fs::remove(box.work() / "f2.ppm");
  write_file(box.work() / "f3.ppm", precious);  // an image already there is left as it is
  const run_result r = box.run({"--scene", file("melt.dump"), "--skip-existing", "-q", "--stats", "-o", box.path("f%d.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(box.work() / "f2.ppm"));
  EXPECT_EQ(read_file(box.work() / "f3.ppm"), precious);
  EXPECT_FALSE(contains(r.err, "frames")) << r.err;  // one frame rendered
}

TEST_F(CliFrames, AMovieHoldsEveryFrame) {
  if (system("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "no ffmpeg here (Debian: ffmpeg)";
  for (const char* name : {"melt.mp4", "melt.webm", "melt.gif"}) {
    const run_result r = box.run({"--scene", file("melt.dump.gz"), "--fps", "10", "-q", "-o", box.path(name)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                              "-of csv=p=0 " + box.path(name) + " > " + box.path("frames.txt");
    ASSERT_EQ(system(probe.c_str()), 0) << name;
    EXPECT_EQ(std::stoi(read_file(box.work() / "frames.txt")), 5) << name;
  }
  EXPECT_TRUE(box.leftovers().empty());
  // Without ffmpeg on PATH: one line saying which package to install.
  run_options o;
  o.env = {"PATH=/nonexistent"};
  const run_result r = box.run({"--scene", file("melt.dump"), "-o", box.path("no.mp4")}, o);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "writing a movie needs ffmpeg, which is not on PATH (Debian: apt-get install ffmpeg)"))
      << r.err;
}

TEST_F(CliFrames, EachViewFitsTheBoxWhole) {
  std::vector<std::string> pictures;
  for (const char* view : {"corner", "x", "y", "z"})
    for (const char* projection : {"perspective", "orthographic"}) {
      const run_result r = box.run({"--scene", file("same.gsd"), "--view", view, "--projection", projection, "-q",
                                    "-o", box.path("v.ppm")});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const ppm p = parse_ppm(read_file(box.work() / "v.ppm"));
      // Whole: no particle pixel on the picture's top or bottom row.
      for (int64_t row : {int64_t(0), p.height - 1})
        for (int64_t i = 0; i < p.width; ++i)
          EXPECT_EQ(uint8_t(p.pixels[size_t(3 * (row * p.width + i) + 2)]), 255) << view << " " << projection;
      EXPECT_GT(particle_pixels(p), size_t(p.width * p.height / 10)) << view << " " << projection;
      pictures.push_back(p.pixels);
    }
  for (size_t a = 0; a < pictures.size(); ++a)
    for (size_t b = a + 1; b < pictures.size(); ++b) EXPECT_NE(pictures[a], pictures[b]) << a << " " << b;
}

}  // namespace
