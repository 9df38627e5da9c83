// Run-time dispatch as an older CPU sees it: RAYCAST_MAX_ISA caps what raycast
// believes this CPU has, so auto's choice and the refusal of a backend the CPU
// lacks are tested here even on a machine with AVX-512.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_runner.h"
#include "cloud.h"
#include "simd/cpu.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::run_options;
using raycast_test::run_result;

run_options capped(const std::string& isa) {
  run_options o;
  o.env = {"RAYCAST_MAX_ISA=" + isa};
  return o;
}

// The caps this architecture knows, lowest first.
#if defined(__aarch64__)
const std::vector<std::string> caps = {"scalar", "neon"};
#else
const std::vector<std::string> caps = {"scalar", "sse2", "avx2", "avx512"};
#endif

// What auto may pick on this machine under each cap: the best available.
std::string expected_auto(const std::string& cap) {
  const raycast::cpu_features& f = raycast::cpu();  // this process is not capped
  if (cap == "scalar") return "scalar";
  if (f.neon) return "neon";  // AArch64: any cap above scalar leaves NEON
  if (cap == "sse2") return f.sse2 ? "sse2" : "scalar";
  if (cap == "avx2") return f.avx2 ? "avx2" : f.sse2 ? "sse2" : "scalar";
  return f.avx512 ? "avx512" : f.avx2 ? "avx2" : f.sse2 ? "sse2" : "scalar";
}

TEST(Dispatch, AutoPicksTheBestBackendTheCappedCpuRuns) {
  for (const std::string& cap : caps) {
    cli_sandbox box;
    const run_result r = box.run({"--version"}, capped(cap));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("auto backend here: " + expected_auto(cap) + ")"), std::string::npos)
        << "cap " << cap << ": " << r.out;
  }
}

TEST(Dispatch, ABackendTheCpuLacksIsAUsageError) {
#if defined(__aarch64__)
  for (auto [cap, backend] : {std::pair<std::string, std::string>{"scalar", "neon"}}) {
#else
  for (auto [cap, backend] : {std::pair<std::string, std::string>{"avx2", "avx512"},
                              {"sse2", "avx2"}, {"scalar", "sse2"}}) {
#endif
    cli_sandbox box;
    const run_result r = box.run({"--backend", backend, "-o", "x.png"}, capped(cap));
    EXPECT_EQ(r.exit_code, 2) << cap << " " << backend << ": " << r.err;
    EXPECT_NE(r.err.find("--backend"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("cannot run"), std::string::npos) << r.err;
    EXPECT_TRUE(box.entries().empty());
  }
}

// The other architecture's backends are known names, refused with the reason.
TEST(Dispatch, AnotherArchitecturesBackendIsAUsageError) {
#if defined(__aarch64__)
  const std::string other = "avx2", why = "exists only in x86-64 builds";
#else
  const std::string other = "neon", why = "exists only in AArch64 builds";
#endif
  cli_sandbox box;
  const run_result r = box.run({"--backend", other, "-o", "x.ppm"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--backend"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

// Whatever the CPU, the default (exact) output is the same bytes.
TEST(Dispatch, EveryCapGivesTheSameImage) {
  cli_sandbox box;
  std::string first;
  for (const std::string& cap : caps) {
    ASSERT_EQ(box.run({"-w", "203", "-o", cap + ".ppm"}, capped(cap)).exit_code, 0) << cap;
    const std::string bytes = raycast_test::read_file(box.work() / (cap + ".ppm"));
    if (first.empty()) first = bytes;
    EXPECT_EQ(bytes, first) << "cap " << cap;
  }
}

// A hit's AO rays walk four or eight to a vector, by what the CPU runs
// (light/lanes.h): a cap below avx2 leaves four. With the backend held
// fixed, the lane width is all that differs, and the picture is the same
// bytes (a random box: spheres listed in several cells each).
TEST(Dispatch, AoRaysWalkedInEitherLaneWidthGiveTheSameImage) {
  if (!raycast::cpu().avx2) GTEST_SKIP() << "no AVX2 here: the four-lane walk alone";
  cli_sandbox box;
  raycast::api::scene p = raycast_test::particle_box_random(3000);
  p.cam.width = 240;
  p.cam.height = 135;
  for (raycast::sphere& s : p.spheres) {
    s.shade = raycast::shading::lit;
    s.color = raycast::color(0.8, 0.6, 0.4);
  }
  raycast_test::write_file(box.work() / "box.json", raycast_test::cloud_json(p));
  const std::string distance = std::to_string(5 * p.spheres[0].radius);
  std::string first;
  for (const std::string& cap : {std::string("sse2"), std::string("avx2")}) {
    const run_result r = box.run({"--scene", "box.json", "--backend", "sse2", "--light", "0.3,1,0.6", "--shadows",
                                  "--ao", "8", "--ao-distance", distance, "-o", cap + ".ppm"},
                                 capped(cap));
    ASSERT_EQ(r.exit_code, 0) << cap << ": " << r.err;
    const std::string bytes = raycast_test::read_file(box.work() / (cap + ".ppm"));
    if (first.empty()) first = bytes;
    EXPECT_EQ(bytes, first) << "cap " << cap;
  }
  // The spheres are lit and their AO rays were cast: without them the picture differs.
  const run_result r = box.run({"--scene", "box.json", "--backend", "sse2", "--light", "0.3,1,0.6", "--shadows",
                                "-o", "no-ao.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(raycast_test::read_file(box.work() / "no-ao.ppm") != first) << "no AO ray changed the picture";
}

}  // namespace
