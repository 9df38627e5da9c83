// The `raycast` executable as a user runs it: what it writes, what it refuses,
// and that a failure never leaves a damaged or half-written file behind.
// (Images read back through OpenImageIO are checked in test_cli_images.cpp,
// so that only those tests pay for loading the library.)
#include <gtest/gtest.h>


#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "render_support.h"

namespace {

using namespace raycast;
using raycast_test::cli_sandbox;
using raycast_test::compare;
using raycast_test::count_lines;
using raycast_test::image;
using raycast_test::parse_ppm;
using raycast_test::have_image_module;
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

using raycast_test::contains;
using raycast_test::expect_one_error_line;

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
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
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
    EXPECT_EQ(r.err.find("\n  lists ") != std::string::npos, lit) << r.err;
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
    // The render gathered the near-field lists of the spheres it saw: both.
    const size_t l = r.err.find("\n  lists ");
    ASSERT_NE(l, std::string::npos) << r.err;
    size_t lists = 0;
    std::istringstream(r.err.substr(l + 9)) >> lists;
    EXPECT_EQ(lists, 2u) << r.err;
    EXPECT_NE(r.err.find("near-field lists, "), std::string::npos) << r.err;
  }
}

// Flags take no value: given twice they mean the same as once.
TEST_F(Cli, FlagsMayBeRepeated) {
  const run_result r = box.run({"-q", "--quiet", "-o", "sky.ppm"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.ppm"});
}


}  // namespace
