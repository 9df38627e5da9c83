// The `raycast` executable as a user runs it: what it writes, what it refuses,
// and that a failure never leaves a damaged or half-written file behind.
// (Images read back through OpenImageIO are checked in test_cli_images.cpp,
// so that only those tests pay for loading the library.)
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"
#include "render_support.h"

namespace {

using namespace raycast;
using raycast_test::cli_sandbox;
using raycast_test::compare;
using raycast_test::count_lines;
using raycast_test::have_image_module;
using raycast_test::image;
using raycast_test::parse_ppm;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;
using raycast_test::write_file;

namespace fs = std::filesystem;

const std::string default_header = "P6\n400 225\n255\n";

image from_ppm_pixels(const std::string& pixels, int64_t w, int64_t h) {
  image img(w, h, pixel_format::rgb8);
  img.bytes.assign(pixels.begin(), pixels.end());
  return img;
}

// What the CLI must write by default: the renderer with default options.
const image& default_render() {
  static const image img = raycast_test::render_with(
      renderer(raycast_test::make_scene(), render_options{}), pixel_format::rgb8);
  return img;
}

const image& default_reference() {
  static const image img =
      raycast_test::render_with_reference(raycast_test::make_scene(), pixel_format::rgb8);
  return img;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// One line "raycast: error: ..." on standard error, nothing on standard output.
void expect_one_error_line(const run_result& r, const std::string& mentions) {
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << r.err;
  EXPECT_EQ(r.err.rfind("raycast: error: ", 0), 0u) << r.err;
  EXPECT_TRUE(contains(r.err, mentions)) << "want '" << mentions << "' in: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

class Cli : public ::testing::Test {
 protected:
  cli_sandbox box;
};

// ---------------------------------------------------------------- info

TEST_F(Cli, VersionNamesTheProgramAndTheAutoBackend) {
  const run_result r = box.run({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(count_lines(r.out), 1u) << r.out;
  EXPECT_TRUE(contains(r.out, "raycast")) << r.out;
  EXPECT_TRUE(contains(r.out, "auto backend")) << r.out;
  EXPECT_TRUE(contains(r.out, std::string(to_string(best_backend())))) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(Cli, HelpExitsZeroAndListsTheOptions) {
  const run_result r = box.run({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--output", "--width", "--height", "--aspect", "--backend", "--threads"})
    EXPECT_TRUE(contains(r.out, opt)) << opt;
  EXPECT_TRUE(box.entries().empty());
}

// ---------------------------------------------------------------- PPM and stdout

TEST_F(Cli, DefaultPpmEqualsTheRendererAndTheReference) {
  const run_result r = box.run({"-o", "sky.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "no progress when standard error is not a terminal: " << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.ppm"});

  const auto p = parse_ppm(read_file(box.work() / "sky.ppm"));
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.header, default_header);
  const image got = from_ppm_pixels(p.pixels, 400, 225);
  EXPECT_EQ(got.bytes, default_render().bytes) << compare(got, default_render()).where();
  EXPECT_LE(compare(got, default_reference()).max, 1) << compare(got, default_reference()).where();
  // The check pixels, exactly.
  const int want[2][5] = {{0, 0, 163, 200, 255}, {224, 399, 220, 234, 255}};
  for (const auto& w : want)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(got.byte(w[0], w[1], k), w[2 + k]);
}

TEST_F(Cli, StdoutStreamIsTheSameP6AsThePpmFile) {
  const run_result file = box.run({"-o", box.path("sky.ppm")});
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const auto p = parse_ppm(read_file(box.work() / "sky.ppm"));
  ASSERT_EQ(p.error, "");
  fs::remove(box.work() / "sky.ppm");

  const run_result r = box.run({"-o", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  ASSERT_EQ(r.out.size(), default_header.size() + 400 * 225 * 3);
  EXPECT_EQ(r.out.substr(0, default_header.size()), default_header);
  EXPECT_TRUE(r.out.substr(default_header.size()) == p.pixels) << "stdout pixels differ from the .ppm";
  EXPECT_TRUE(box.entries().empty()) << "-o - wrote a file";
}

// Every camera and sky option reaches the render.
TEST_F(Cli, OptionsReachTheRender) {
  const run_result r = box.run({"--width", "64", "--aspect", "2:1", "--viewport-height", "3",
                                "--focal-length", "0.5", "--origin", "5,-5,2", "--sky-bottom",
                                "0.9,0.8,0.7", "--sky-top", "0.1,0.2,0.3", "-o", "custom.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  api::camera cp;
  cp.width = 64;
  cp.aspect = 2.0;
  cp.viewport_height = 3;
  cp.focal_length = 0.5;
  cp.lookfrom = point3(5, -5, 2);
  const scene s = raycast_test::make_scene(cp, sky{color(0.9, 0.8, 0.7), color(0.1, 0.2, 0.3)});
  ASSERT_EQ(s.cam.image_height, 32);

  const auto p = parse_ppm(read_file(box.work() / "custom.ppm"));
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.header, "P6\n64 32\n255\n");
  const image got = from_ppm_pixels(p.pixels, 64, 32);
  const image want = raycast_test::render_with(renderer(s, render_options{}), pixel_format::rgb8);
  EXPECT_EQ(got.bytes, want.bytes) << compare(got, want).where();
  const image ref = raycast_test::render_with_reference(s, pixel_format::rgb8);
  EXPECT_LE(compare(got, ref).max, 1) << compare(got, ref).where();
}

TEST_F(Cli, ExplicitHeightAndAspectForms) {
  ASSERT_EQ(box.run({"--width", "30", "--height", "7", "-o", "h.ppm"}).exit_code, 0);
  EXPECT_EQ(parse_ppm(read_file(box.work() / "h.ppm")).header, "P6\n30 7\n255\n");
  ASSERT_EQ(box.run({"--width", "30", "--aspect", "3:2", "-o", "a.ppm"}).exit_code, 0);
  ASSERT_EQ(box.run({"--width", "30", "--aspect", "1.5", "-o", "b.ppm"}).exit_code, 0);
  const std::string a = read_file(box.work() / "a.ppm");
  EXPECT_EQ(parse_ppm(a).header, "P6\n30 20\n255\n");
  EXPECT_TRUE(a == read_file(box.work() / "b.ppm")) << "--aspect 3:2 and --aspect 1.5 differ";
}

TEST_F(Cli, BackendsAndThreadCounts) {
  const scene s = raycast_test::make_scene();
  ASSERT_EQ(box.run({"--backend", "reference", "-o", "ref.ppm"}).exit_code, 0);
  EXPECT_TRUE(parse_ppm(read_file(box.work() / "ref.ppm")).pixels ==
              std::string(default_reference().bytes.begin(), default_reference().bytes.end()))
      << "--backend reference differs from render_reference";

  ASSERT_EQ(box.run({"--backend", "scalar", "--precision", "exact", "-o", "scalar.ppm"}).exit_code, 0);
  const image scalar = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb8);
  EXPECT_TRUE(parse_ppm(read_file(box.work() / "scalar.ppm")).pixels ==
              std::string(scalar.bytes.begin(), scalar.bytes.end()))
      << "--backend scalar differs from render_scalar";

  ASSERT_EQ(box.run({"--backend", "auto", "--threads", "1", "-o", "t1.ppm"}).exit_code, 0);
  EXPECT_TRUE(parse_ppm(read_file(box.work() / "t1.ppm")).pixels ==
              std::string(default_render().bytes.begin(), default_render().bytes.end()));
}

// The CLI renders and writes an image in bands of about 2^20 pixels: a
// 1500x1000 image is two bands, each rendered on two threads, and the file
// must be the library's whole image rendered in one call. (Thread invariance
// itself: test_equivalence.cpp, ThreadEquivalence.)
TEST_F(Cli, BandsAssembleTheWholeImage) {
  ASSERT_EQ(box.run({"--width", "1500", "--height", "1000", "--threads", "2", "-q", "-o", "bands.ppm"})
                .exit_code,
            0);
  const image whole = raycast_test::render_with(
      renderer(raycast_test::make_scene(raycast_test::sized(1500, 1000)), render_options{}),
      pixel_format::rgb8);
  EXPECT_TRUE(parse_ppm(read_file(box.work() / "bands.ppm")).pixels ==
              std::string(whole.bytes.begin(), whole.bytes.end()))
      << "the banded file differs from the image rendered in one call";
}

// The recipe of README "Rendering across machines": a frame split into
// four regions, each rendered by its own process as a scheduler's job would
// be, then pasted together, is the single render byte for byte -- many
// samples, seeded, on two threads against one.
TEST_F(Cli, FourRegionProcessesAssembleTheSingleRender) {
  const std::vector<std::string> common = {"--scene", "world", "--samples", "8", "--seed", "3", "-w", "203", "-q"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = common;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  ASSERT_EQ(box.run(with({"--threads", "2", "-o", "full.ppm"})).exit_code, 0);
  const raycast_test::ppm full = parse_ppm(read_file(box.work() / "full.ppm"));
  ASSERT_EQ(full.error, "");
  ASSERT_EQ(full.width, 203);
  const int64_t W = full.width, H = full.height;
  const int64_t xs[] = {0, 77, W}, ys[] = {0, 50, H};
  std::string pasted(full.pixels.size(), '\0');
  for (int q = 0; q < 4; ++q) {
    const int64_t x0 = xs[q % 2], x1 = xs[q % 2 + 1], y0 = ys[q / 2], y1 = ys[q / 2 + 1];
    const std::string name = "part" + std::to_string(q) + ".ppm";
    const run_result r = box.run(with({"--threads", "1", "--region",
                                       std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) +
                                           "," + std::to_string(y1),
                                       "-o", name}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const raycast_test::ppm part = parse_ppm(read_file(box.work() / name));
    ASSERT_EQ(part.error, "");
    ASSERT_EQ(part.width, x1 - x0);
    ASSERT_EQ(part.height, y1 - y0);
    for (int64_t y = y0; y < y1; ++y)
      pasted.replace(size_t((y * W + x0) * 3), size_t((x1 - x0) * 3), part.pixels, size_t((y - y0) * (x1 - x0) * 3),
                     size_t((x1 - x0) * 3));
  }
  EXPECT_TRUE(pasted == full.pixels) << "the pasted regions differ from the single render";
}

TEST_F(Cli, FastPrecisionStaysWithinOneLsbOfTheReference) {
  const run_result r = box.run({"--precision", "fast", "-o", "fast.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto p = parse_ppm(read_file(box.work() / "fast.ppm"));
  ASSERT_EQ(p.error, "");
  const image got = from_ppm_pixels(p.pixels, 400, 225);
  EXPECT_LE(compare(got, default_reference()).max, 1) << compare(got, default_reference()).where();
}

// ---------------------------------------------------------------- formats

struct format_case {
  const char* name;
  std::vector<std::string> args;
  const char* file;
  std::string magic;  // the file's first bytes
};

class CliFormat : public Cli, public ::testing::WithParamInterface<format_case> {};

TEST_P(CliFormat, ExtensionOrFormatOptionPicksTheEncoder) {
  std::vector<std::string> args = GetParam().args;
  args.insert(args.end(), {"--width", "16", "--height", "9"});
  const run_result r = box.run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(box.entries(), std::vector<std::string>{GetParam().file});
  const std::string data = read_file(box.work() / GetParam().file);
  EXPECT_EQ(data.substr(0, GetParam().magic.size()), GetParam().magic);
}

const std::string png_magic("\x89PNG\r\n\x1a\n", 8);
const std::string jpg_magic("\xFF\xD8\xFF", 3);
const std::string tif_magic("II*\0", 4);  // little-endian TIFF, as x86 writes it
const std::string exr_magic("\x76\x2F\x31\x01", 4);

const format_case format_cases[] = {
    {"png", {"-o", "a.png"}, "a.png", png_magic},
    {"png_upper_case", {"-o", "a.PNG"}, "a.PNG", png_magic},
    {"pnm", {"-o", "a.pnm"}, "a.pnm", "P6\n16 9\n255\n"},
    {"jpeg", {"-o", "a.jpeg"}, "a.jpeg", jpg_magic},
    {"tiff", {"-o", "a.tiff"}, "a.tiff", tif_magic},
    {"exr", {"-o", "a.exr"}, "a.exr", exr_magic},
    {"format_overrides_unknown_extension", {"-o", "a.dat", "--format", "tif"}, "a.dat", tif_magic},
    {"format_overrides_known_extension", {"-o", "a.png", "--format", "ppm"}, "a.png", "P6\n"},
};

std::string format_name(const ::testing::TestParamInfo<format_case>& p) { return p.param.name; }

INSTANTIATE_TEST_SUITE_P(Formats, CliFormat, ::testing::ValuesIn(format_cases), format_name);

// ---------------------------------------------------------------- usage errors

struct usage_case {
  std::string name;
  std::vector<std::string> args;  // "{out}" stands for <tmp>/out.png
  const char* mentions;
};

void PrintTo(const usage_case& c, std::ostream* os) {
  for (const std::string& a : c.args) *os << (a.empty() ? "''" : a) << " ";
}

class CliUsageError : public Cli, public ::testing::WithParamInterface<usage_case> {};

TEST_P(CliUsageError, ExitsTwoWithOneLineNamingTheOptionAndWritesNothing) {
  std::vector<std::string> args;
  for (const std::string& a : GetParam().args) args.push_back(a == "{out}" ? box.path("out.png") : a);
  const run_result r = box.run(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  expect_one_error_line(r, GetParam().mentions);
  EXPECT_TRUE(box.entries().empty()) << "a refused run wrote " << box.entries().front();
}

const usage_case usage_cases[] = {
    {"width_zero", {"--width", "0", "-o", "{out}"}, "--width"},
    {"width_equals_empty", {"--width=", "-o", "{out}"}, "--width"},
    {"width_negative", {"--width", "-5", "-o", "{out}"}, "--width"},
    {"width_with_unit", {"--width", "400px", "-o", "{out}"}, "--width"},
    {"width_empty", {"--width", "", "-o", "{out}"}, "--width"},
    {"width_exponent", {"--width", "1e3", "-o", "{out}"}, "--width"},
    {"width_over_max", {"--width", "16777217", "-o", "{out}"}, "--width"},
    {"width_overflow", {"--width", "99999999999999999999", "-o", "{out}"}, "--width"},
    {"width_repeated", {"--width", "10", "--width", "20", "-o", "{out}"}, "--width"},
    {"height_zero", {"--height", "0", "-o", "{out}"}, "--height"},
    {"aspect_zero", {"--aspect", "0", "-o", "{out}"}, "--aspect"},
    {"aspect_text", {"--aspect", "abc", "-o", "{out}"}, "--aspect"},
    {"aspect_zero_denominator", {"--aspect", "16:0", "-o", "{out}"}, "--aspect"},
    {"aspect_height_over_max", {"--aspect", "1e-7", "-o", "{out}"}, "--aspect"},
    {"viewport_nan", {"--viewport-height", "nan", "-o", "{out}"}, "--viewport-height"},
    {"viewport_negative", {"--viewport-height", "-1", "-o", "{out}"}, "--viewport-height"},
    {"viewport_overflow", {"--viewport-height", "1e400", "-o", "{out}"}, "--viewport-height"},
    {"focal_inf", {"--focal-length", "inf", "-o", "{out}"}, "--focal-length"},
    {"focal_zero", {"--focal-length", "0", "-o", "{out}"}, "--focal-length"},
    {"origin_two", {"--origin", "1,2", "-o", "{out}"}, "--origin"},
    {"origin_four", {"--origin", "1,2,3,4", "-o", "{out}"}, "--origin"},
    {"origin_text", {"--origin", "1,x,3", "-o", "{out}"}, "--origin"},
    {"origin_inf", {"--origin", "1,inf,3", "-o", "{out}"}, "--origin"},
    {"sky_top_two", {"--sky-top", "1,1", "-o", "{out}"}, "--sky-top"},
    {"sky_bottom_nan", {"--sky-bottom", "1,nan,1", "-o", "{out}"}, "--sky-bottom"},
    {"sky_top_huge", {"--sky-top", "1,1e31,1", "-o", "{out}"}, "--sky-top"},
    {"sky_bottom_overflow", {"--sky-bottom", "1e400,0,0", "-o", "{out}"}, "--sky-bottom"},
    {"focal_minus_inf", {"--focal-length", "-inf", "-o", "{out}"}, "--focal-length"},
    {"focal_negative", {"--focal-length", "-2", "-o", "{out}"}, "--focal-length"},
    {"aspect_nan", {"--aspect", "nan", "-o", "{out}"}, "--aspect"},
    {"aspect_inf", {"--aspect", "inf", "-o", "{out}"}, "--aspect"},
    {"aspect_negative_ratio", {"--aspect", "-16:9", "-o", "{out}"}, "--aspect"},
    {"aspect_garbage", {"--aspect", "16:9x", "-o", "{out}"}, "--aspect"},
    {"height_with_unit", {"--height", "225px", "-o", "{out}"}, "--height"},
    {"height_over_max", {"--height", "16777217", "-o", "{out}"}, "--height"},
    {"viewport_zero", {"--viewport-height", "0", "-o", "{out}"}, "--viewport-height"},
    {"viewport_garbage", {"--viewport-height", "2.0.0", "-o", "{out}"}, "--viewport-height"},
    {"origin_overflow", {"--origin", "0,0,1e999", "-o", "{out}"}, "--origin"},
    {"origin_empty_component", {"--origin", "1,,3", "-o", "{out}"}, "--origin"},
    {"threads_text", {"--threads", "two", "-o", "{out}"}, "--threads"},
    {"format_unknown", {"--format", "bmp", "-o", "{out}"}, "--format"},
    {"stdout_not_ppm", {"--format", "png", "-o", "-"}, "--format"},
    {"extension_unknown", {"-o", "out.bmp"}, "--output"},
    {"extension_missing", {"-o", "out"}, "--output"},
    {"output_empty", {"-o", ""}, "--output"},
    {"output_missing", {}, "--output"},
    {"threads_negative", {"--threads", "-1", "-o", "{out}"}, "--threads"},
    {"threads_too_many", {"--threads", "1025", "-o", "{out}"}, "--threads"},
    {"backend_unknown", {"--backend", "nope", "-o", "{out}"}, "--backend"},
    {"precision_unknown", {"--precision", "nope", "-o", "{out}"}, "--precision"},
    {"unknown_option", {"--bogus", "-o", "{out}"}, "--bogus"},
    {"scene_unknown", {"--scene", "cornell-box", "-o", "{out}"}, "red-sphere, normals, world"},
    {"samples_over_max", {"--samples", "1048577", "-o", "{out}"}, "--samples"},
    {"region_empty_width", {"--region", "5,0,5,8", "-o", "{out}"}, "--region"},
    {"region_below_zero", {"--region", "0,-1,8,8", "-o", "{out}"}, "--region"},
    {"region_past_height", {"--region", "0,0,8,226", "-o", "{out}"}, "--region"},
    {"region_reversed", {"--region", "8,8,0,0", "-o", "{out}"}, "--region"},
};

std::string usage_name(const ::testing::TestParamInfo<usage_case>& p) { return p.param.name; }

INSTANTIATE_TEST_SUITE_P(Options, CliUsageError, ::testing::ValuesIn(usage_cases), usage_name);

// Every option that takes a value, each way a value can be wrong: given twice
// (even the same value), empty, missing at the end of the line, of the wrong
// type, and out of range where it has a range.
struct valued_option {
  const char* name;         // the long name, as the message names it
  const char* spelling;     // as given on the command line (a short form where there is one)
  const char* good;         // a valid value ("{out}" for the output)
  const char* wrong_type;   // not a value of the option's type; null: any text is
  const char* out_of_range; // of the right type but outside what is allowed; null: no range
};

const valued_option valued_options[] = {
    {"--output", "-o", "{out}", nullptr, nullptr},
    {"--width", "-w", "16", "sixteen", "-16"},
    {"--height", "--height", "9", "9.5", "-1"},
    {"--aspect", "--aspect", "2:1", "wide", "-2:1"},
    {"--viewport-height", "--viewport-height", "2", "2m", "-2"},
    {"--focal-length", "--focal-length", "1", "0x1p", "-1"},
    {"--origin", "--origin", "0,0,0", "a,b,c", "0,0,1e400"},
    {"--lookfrom", "--lookfrom", "0,0,0", "0:0:0", "1e400,0,0"},
    {"--lookat", "--lookat", "0,0,-1", "here", "0,0,-inf"},
    {"--vup", "--vup", "0,1,0", "up", "0,0,0"},
    {"--vfov", "--vfov", "90", "ninety", "180"},
    {"--sky-bottom", "--sky-bottom", "1,1,1", "white", "1,1,1e31"},
    {"--sky-top", "--sky-top", "0.5,0.7,1", "blue", "-1e31,0,0"},
    {"--format", "--format", "ppm", "bmp", nullptr},
    {"--backend", "--backend", "scalar", "fastest", nullptr},
    {"--precision", "--precision", "exact", "double", nullptr},
    {"--threads", "--threads", "2", "2.0", "1025"},
    {"--scene", "--scene", "world", "nowhere", nullptr},
    {"--samples", "--samples", "4", "four", "0"},
    {"--sampler", "--sampler", "sobol", "halton", nullptr},
    {"--seed", "--seed", "7", "-1", "18446744073709551616"},
    {"--region", "--region", "0,0,8,8", "0,0,8", "0,0,401,8"},
};

std::vector<usage_case> every_option_cases() {
  std::vector<usage_case> cases;
  for (const valued_option& o : valued_options) {
    const std::string id = std::string(o.name).substr(2);
    const bool is_output = id == "output";
    auto add = [&](const std::string& kind, std::vector<std::string> args) {
      if (!is_output) args.insert(args.end(), {"-o", "{out}"});
      std::string name = id + "_" + kind;
      std::replace(name.begin(), name.end(), '-', '_');
      cases.push_back({name, std::move(args), o.name});
    };
    add("repeated", {o.spelling, o.good, o.name, o.good});
    add("empty", {o.spelling, ""});
    if (is_output)
      cases.push_back({"output_missing_value", {"-o"}, o.name});
    else
      cases.push_back({id + "_missing_value", {"-o", "{out}", o.spelling}, o.name});
    if (o.wrong_type) add("wrong_type", {o.spelling, o.wrong_type});
    if (o.out_of_range) add("out_of_range", {o.spelling, o.out_of_range});
  }
  for (usage_case& c : cases) std::replace(c.name.begin(), c.name.end(), '-', '_');
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryOption, CliUsageError, ::testing::ValuesIn(every_option_cases()),
                         usage_name);

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

// --stats: a short block on standard error after the run, stable labels,
// numbers that parse.
TEST_F(Cli, StatsPrintsTimingsRaysAndMemory) {
  write_file(box.work() / "s.json", R"({"camera": {"width": 32, "height": 18},
      "spheres": [{"center": [0, 0, -1], "radius": 0.5}, {"center": [0, -100.5, -1], "radius": 100}]})");
  const run_result r = box.run({"--scene", "s.json", "--samples", "4", "-q", "--stats", "-o", "a.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::istringstream in(r.err);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "raycast stats:");
  std::map<std::string, double> value;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string label, number, unit;
    fields >> label;
    if (label == "peak") fields >> label, label = "peak " + label;
    fields >> number >> unit;
    size_t used = 0;
    value[label] = std::stod(number, &used);
    EXPECT_EQ(used, number.size()) << line;
  }
  for (const char* label : {"load", "prepare", "open", "render", "write", "total", "rays/s", "spheres", "peak RSS"})
    EXPECT_EQ(value.count(label), 1u) << label << " in:\n" << r.err;
  EXPECT_LE(count_lines(r.err), 10u) << r.err;
  EXPECT_EQ(value["spheres"], 2.0);
  EXPECT_GT(value["rays/s"], 0.0);
  EXPECT_GT(value["peak RSS"], 0.0);
  for (const char* label : {"load", "prepare", "open", "render", "write"}) {
    EXPECT_GE(value[label], 0.0) << label;
    EXPECT_LE(value[label], value["total"]) << label;
  }
  // 32 x 18 pixels, 4 samples each.
  EXPECT_NE(r.err.find("(2304 rays)"), std::string::npos) << r.err;
}

// The stages account for the run: a PNG's image library is loaded when the
// output is opened, the run's dearest stage, and its own line says so.
TEST_F(Cli, StatsStagesAddUpToTheTotal) {
  const run_result r = box.run({"--scene", "world", "-q", "--stats", "-o", "a.png"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, double> value;
  std::istringstream in(r.err);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string label;
    double seconds = 0;
    if (fields >> label >> seconds) value[label] = seconds;
  }
  const double stages = value["load"] + value["prepare"] + value["open"] + value["render"] + value["write"];
  // What no line counts: the process's start, parsing the options, the
  // camera's setup: a few milliseconds at most, next to the image library's load.
  EXPECT_GE(stages, 0.9 * value["total"] - 0.005) << r.err;
  EXPECT_GT(value["open"], value["render"]) << r.err;
}

// With shadows or AO, --stats adds what their structures took of prepare.
TEST_F(Cli, StatsSayWhatTheLightsStructuresTook) {
  write_file(box.work() / "s.json", R"({"camera": {"width": 32, "height": 18},
      "spheres": [{"center": [0, 0, -1], "radius": 0.5, "shade": "lit", "color": [0.8, 0.3, 0.3]},
                  {"center": [0, -100.5, -1], "radius": 100, "shade": "lit", "color": [0.8, 0.8, 0.0]}]})");
  for (const bool lit : {false, true}) {
    std::vector<std::string> args = {"--scene", "s.json", "-q", "--stats", "-o", "a.ppm"};
    if (lit) args.insert(args.end(), {"--light", "1,1,1", "--shadows", "--ao", "4"});
    const run_result r = box.run(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const size_t at = r.err.find("\n  light ");
    EXPECT_EQ(at != std::string::npos, lit) << r.err;
    if (at == std::string::npos) continue;
    std::istringstream fields(r.err.substr(at + 1));
    std::string label;
    double light = -1, prepare = -1;
    fields >> label >> light;
    const size_t p = r.err.find("\n  prepare ");
    ASSERT_NE(p, std::string::npos);
    std::istringstream(r.err.substr(p + 11)) >> prepare;
    EXPECT_GE(light, 0.0);
    EXPECT_LE(light, prepare) << r.err;
    EXPECT_NE(r.err.find(" MB for shadow and AO rays)"), std::string::npos) << r.err;
  }
}

// Flags take no value: given twice they mean the same as once.
TEST_F(Cli, FlagsMayBeRepeated) {
  const run_result r = box.run({"-q", "--quiet", "-o", "sky.ppm"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.ppm"});
}

// However the format is unsupported, the message lists the supported ones.
TEST_F(Cli, EveryUnsupportedFormatListsTheSupportedOnes) {
  const std::vector<std::vector<std::string>> ways = {
      {"-o", "out.bmp"}, {"-o", "out"},  {"-o", "out.tar.gz"}, {"-o", "out.png.bak"},
      {"-o", "dir.png/out"}, {"-o", "out.png", "--format", "gif"}, {"-o", "out."}};
  for (const auto& args : ways) {
    const run_result r = box.run(args);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    for (const char* f : {"png", "ppm", "jpg", "tif", "exr"})
      EXPECT_TRUE(contains(r.err, f)) << f << " missing from: " << r.err;
  }
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(Cli, UnknownExtensionListsTheSupportedOnes) {
  const run_result r = box.run({"-o", "out.bmp"});
  EXPECT_EQ(r.exit_code, 2);
  for (const char* ext : {".png", ".ppm", ".jpg", ".tif", ".exr"})
    EXPECT_TRUE(contains(r.err, ext)) << ext << " missing from: " << r.err;
}

// A name as long as the file system takes (255 bytes here) is written: the
// temporary's own name, longer by its prefix and suffix, is cut to fit.
TEST_F(Cli, TheLongestFileNameIsWritten) {
  const long name_max = pathconf(box.work().c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 8);
  for (const char* ext : {".ppm", ".png"}) {
    if (std::string(ext) == ".png" && !have_image_module()) continue;
    const std::string name = std::string(size_t(name_max) - 4, 'n') + ext;
    for (int twice = 0; twice < 2; ++twice) {  // created, then replaced
      const run_result r = box.run({"-w", "16", "-o", box.path(name)});
      EXPECT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(box.entries(), std::vector<std::string>{name});
    }
    fs::remove(box.work() / name);
  }
}

TEST_F(Cli, UsageErrorLeavesAnExistingFileIntact) {
  write_file(box.work() / "out.png", "precious");
  const run_result r = box.run({"--width", "0", "-o", box.path("out.png")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(read_file(box.work() / "out.png"), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"out.png"});
}

// ---------------------------------------------------------------- unwritable destinations

TEST_F(Cli, MissingDirectoryExitsOneNamingTheFile) {
  const std::string dest = box.path("missing_dir/a.png");
  const run_result r = box.run({"-o", dest});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(Cli, DestinationThatIsADirectoryExitsOne) {
  fs::create_directory(box.work() / "a_directory_that_exists");
  const std::string dest = box.path("a_directory_that_exists");
  const run_result r = box.run({"-o", dest, "--format", "png"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_TRUE(fs::is_directory(dest));
  EXPECT_EQ(box.entries(), std::vector<std::string>{"a_directory_that_exists"});
}

TEST_F(Cli, ReadOnlyDirectoryExitsOne) {
  const fs::path dir = box.work() / "read_only";
  fs::create_directory(dir);
  ASSERT_EQ(chmod(dir.c_str(), 0555), 0);
  run_options opts;
  if (access(dir.c_str(), W_OK) == 0) {
    if (geteuid() != 0) GTEST_SKIP() << "a 0555 directory is still writable here";
    // Root writes anywhere: run the CLI as nobody, whom the mode does stop.
    opts.run_as = std::pair<uid_t, gid_t>{65534, 65534};
    box.open_to_others();
  }
  const std::string dest = (dir / "a.png").string();
  const run_result r = box.run({"-o", dest}, opts);
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"read_only"});
}

// /proc refuses new files even to root.
TEST_F(Cli, DirectoryNoOneCanWriteToExitsOne) {
  const std::string dest = "/proc/raycast-test-sky.png";
  const run_result r = box.run({"-o", dest});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_FALSE(fs::exists(dest));
}

TEST_F(Cli, DevFullExitsOne) {
  // A device is written in place, never replaced (even where /dev is writable):
  // see DeviceNodeDestinationIsWrittenNotReplaced, on a node of our own.
  const run_result r = box.run({"-o", "/dev/full", "--format", "ppm"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "/dev/full");
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

// A destination that is a character device (here a node of /dev/full's
// device, 1:7, in the temporary directory) is written to, not replaced by a
// regular file: `raycast -o /dev/full` as root must not destroy /dev/full.
TEST_F(Cli, DeviceNodeDestinationIsWrittenNotReplaced) {
  const fs::path node = box.work() / "full";
  if (mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0)
    GTEST_SKIP() << "cannot create a device node here: " << std::strerror(errno);
  const run_result r = box.run({"-o", node.string(), "--format", "ppm"});
  struct stat st {};
  ASSERT_EQ(stat(node.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced by a regular file of "
                                   << st.st_size << " bytes";
  EXPECT_EQ(r.exit_code, 1) << "writing to a full device must fail";
  expect_one_error_line(r, node.string());
}

// Through a symbolic link the file it names is replaced (the link stays), and a
// replaced file keeps its permissions.
TEST_F(Cli, SymlinkDestinationReplacesTargetAndKeepsMode) {
  write_file(box.work() / "real.ppm", "precious");
  ASSERT_EQ(chmod((box.work() / "real.ppm").c_str(), 0600), 0);
  fs::create_symlink("real.ppm", box.work() / "link.ppm");
  const run_result r = box.run({"-o", box.path("link.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(box.work() / "link.ppm"));
  struct stat st {};
  ASSERT_EQ(stat((box.work() / "real.ppm").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(st.st_size, 270015);  // header + 400 x 225 x 3
}

// ---------------------------------------------------------------- failures while writing

class CliWriteFailure : public Cli, public ::testing::WithParamInterface<const char*> {};

// A write that fails half-way (the file size limit stands in for a full disk)
// exits 1 naming the file, removes the temporary file and leaves the previous
// file at the destination exactly as it was.
TEST_P(CliWriteFailure, KeepsTheExistingFileAndRemovesTheTemporary) {
  const std::string name = std::string("out.") + GetParam();
  write_file(box.work() / name, "precious");
  run_options opts;
  opts.file_size_limit = 1024;
  const run_result r = box.run({"-o", box.path(name)}, opts);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  expect_one_error_line(r, box.path(name));
  EXPECT_EQ(read_file(box.work() / name), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});
}

std::string extension_name(const ::testing::TestParamInfo<const char*>& p) { return p.param; }

INSTANTIATE_TEST_SUITE_P(Formats, CliWriteFailure,
                         ::testing::Values("ppm", "png", "jpg", "tif", "exr"), extension_name);

TEST_F(Cli, StandardOutputWriteFailureExitsOne) {
  run_options opts;
  opts.stdout_path = "/dev/full";
  const run_result r = box.run({"-o", "-"}, opts);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "standard output")) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

// SIGTERM during a write removes the temporary file and leaves the previous
// file intact.
TEST_F(Cli, TerminationRemovesTheTemporaryFile) {
  // PNG: its encoding runs long enough to be caught mid-write.
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  write_file(box.work() / "big.png", "precious");
  // Large enough that encoding runs for seconds; we stop it at once.
  const pid_t pid = box.start({"--width", "8192", "--height", "8192", "-o", box.path("big.png")});
  bool seen = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    seen = box.output_in_progress(pid).has_value();
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  kill(pid, SIGTERM);
  const run_result r = box.finish(pid);  // also checks that no temporary file remains
  ASSERT_TRUE(seen) << "the file being written never appeared";
  EXPECT_EQ(r.signal, SIGTERM) << "exit code " << r.exit_code << ": " << r.err;
  EXPECT_EQ(read_file(box.work() / "big.png"), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"big.png"});
}

}  // namespace
