// The CLI's PNG, TIFF, EXR and JPEG files, read back through OpenImageIO.
// (Kept apart from test_cli.cpp: only these tests load the library.)
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "render_support.h"
#include "scene/builtin.h"

namespace {

using namespace raycast;
using raycast_test::cli_sandbox;
using raycast_test::compare;
using raycast_test::image;
using raycast_test::run_result;

// The file as an image in the given pixel format, with its stored format.
struct read_back {
  image img;
  OIIO::TypeDesc stored;
  int channels = 0;
  std::string error;
};

read_back read_image(const std::string& path, pixel_format f) {
  read_back r;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    r.error = "cannot open " + path + ": " + OIIO::geterror();
    return r;
  }
  const OIIO::ImageSpec& spec = in->spec();
  r.stored = spec.format;
  r.channels = spec.nchannels;
  if (spec.nchannels != 3) {
    r.error = "want 3 channels, file has " + std::to_string(spec.nchannels);
    return r;
  }
  r.img = image(spec.width, spec.height, f);
  const OIIO::TypeDesc type = f == pixel_format::rgb8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  if (!in->read_image(0, 0, 0, 3, type, r.img.bytes.data())) r.error = in->geterror();
  in->close();
  return r;
}

const scene& default_scene() {
  static const scene s = raycast_test::make_scene();
  return s;
}

class CliImages : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

// 8-bit formats: exactly what the renderer with default options writes, and
// within 1 LSB of the double reference.
TEST_P(CliImages, LosslessEightBitFileEqualsTheRenderer) {
  const std::string name = std::string("sky.") + GetParam();
  const run_result r = box.run({"-o", name});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});

  const read_back f = read_image(box.path(name), pixel_format::rgb8);
  ASSERT_EQ(f.error, "");
  EXPECT_EQ(f.stored, OIIO::TypeDesc::UINT8);
  ASSERT_EQ(f.img.width, 400);
  ASSERT_EQ(f.img.height, 225);

  const image want =
      raycast_test::render_with(renderer(default_scene(), render_options{}), pixel_format::rgb8);
  EXPECT_EQ(f.img.bytes, want.bytes) << compare(f.img, want).where();
  const image ref = raycast_test::render_with_reference(default_scene(), pixel_format::rgb8);
  EXPECT_LE(compare(f.img, ref).max, 1) << compare(f.img, ref).where();
  const int check[2][5] = {{0, 0, 163, 200, 255}, {224, 399, 220, 234, 255}};
  for (const auto& c : check)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(f.img.byte(c[0], c[1], k), c[2 + k]);
}

std::string extension_name(const ::testing::TestParamInfo<const char*>& p) { return p.param; }

INSTANTIATE_TEST_SUITE_P(Formats, CliImages, ::testing::Values("png", "tif"), extension_name);

TEST(CliImagesFloat, ExrCarriesTheLinearColourUnquantized) {
  cli_sandbox box;
  const run_result r = box.run({"-o", "sky.exr"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;

  const read_back f = read_image(box.path("sky.exr"), pixel_format::rgb_f32);
  ASSERT_EQ(f.error, "");
  EXPECT_EQ(f.stored, OIIO::TypeDesc::FLOAT) << "stored as " << f.stored.c_str();
  ASSERT_EQ(f.img.width, 400);
  ASSERT_EQ(f.img.height, 225);

  const image want =
      raycast_test::render_with(renderer(default_scene(), render_options{}), pixel_format::rgb_f32);
  EXPECT_EQ(f.img.bytes, want.bytes) << compare(f.img, want).where();
  const auto d = raycast_test::compare_to_reference_pixels(f.img, default_scene());
  EXPECT_LE(d.max, 1e-6) << d.where();
  // Unquantized: the top-left red, 1 - t/2 with t = 0.720102, is no multiple of 1/255.
  const double red = f.img.value(0, 0, 0);
  EXPECT_NEAR(red, 1 - 0.5 * 0.720102, 1e-6);
  EXPECT_GT(std::abs(red * 255 - std::round(red * 255)), 1e-3);
  EXPECT_EQ(f.img.value(0, 0, 2), 1.0f);
}

TEST(CliImagesFloat, ExrOfASizeOtherThanTheDefault) {
  cli_sandbox box;
  const run_result r = box.run({"--width", "31", "--height", "17", "-o", "small.exr"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const read_back f = read_image(box.path("small.exr"), pixel_format::rgb_f32);
  ASSERT_EQ(f.error, "");
  ASSERT_EQ(f.img.width, 31);
  ASSERT_EQ(f.img.height, 17);
  api::camera p;
  p.width = 31;
  p.height = 17;
  const auto d = raycast_test::compare_to_reference_pixels(f.img, raycast_test::make_scene(p));
  EXPECT_LE(d.max, 1e-6) << d.where();
}

// JPEG is lossy: the right size, and close to the reference.
TEST(CliImagesJpeg, JpegIsTheSkyWithinCompressionError) {
  cli_sandbox box;
  const run_result r = box.run({"-o", "sky.jpg"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const read_back f = read_image(box.path("sky.jpg"), pixel_format::rgb8);
  ASSERT_EQ(f.error, "");
  ASSERT_EQ(f.img.width, 400);
  ASSERT_EQ(f.img.height, 225);
  const image ref = raycast_test::render_with_reference(default_scene(), pixel_format::rgb8);
  double sum = 0;
  for (size_t k = 0; k < ref.bytes.size(); ++k) sum += std::abs(int(f.img.bytes[k]) - int(ref.bytes[k]));
  EXPECT_LE(sum / double(ref.bytes.size()), 1.0);
  EXPECT_LE(compare(f.img, ref).max, 8) << compare(f.img, ref).where();
}

}  // namespace

namespace {

// The picture in the README is tests/golden/sky.png. The default render (here
// as a PPM, which needs no image library) must still be exactly that picture.
TEST(Golden, DefaultRenderIsTheReadmePicture) {
  cli_sandbox box;
  const run_result r = box.run({"-o", "sky.ppm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const raycast_test::ppm p = raycast_test::parse_ppm(raycast_test::read_file(box.work() / "sky.ppm"));
  ASSERT_TRUE(p.error.empty()) << p.error;
  const read_back golden = read_image(RAYCAST_GOLDEN_DIR "/sky.png", pixel_format::rgb8);
  ASSERT_TRUE(golden.error.empty()) << golden.error;
  ASSERT_EQ(golden.img.bytes.size(), p.pixels.size());
  EXPECT_TRUE(std::equal(p.pixels.begin(), p.pixels.end(), golden.img.bytes.begin(),
                         [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; }))
      << "the default sky no longer matches tests/golden/sky.png";
}

}  // namespace

namespace {

// `raycast --scene world -o world.png` is the book's
// ch. 6 picture within 1 LSB (the double reference is the book's formulas,
// tests/test_spheres.cpp), and exactly what the renderer gives; likewise the
// other built-in sphere scenes.
TEST(SphereScenes, PngIsTheBooksPictureWithinOneLsb) {
  for (const char* name : {"world", "normals", "red-sphere"}) {
    SCOPED_TRACE(name);
    cli_sandbox box;
    const run_result r = box.run({"--scene", name, "-o", "scene.png"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const read_back f = read_image(box.path("scene.png"), pixel_format::rgb8);
    ASSERT_EQ(f.error, "");
    ASSERT_EQ(f.img.width, 400);
    ASSERT_EQ(f.img.height, 225);
    const scene s = raycast_test::make_scene({}, {}, *builtin_spheres(name));
    const image ref = raycast_test::render_with_reference(s, pixel_format::rgb8);
    EXPECT_LE(compare(f.img, ref).max, 1) << compare(f.img, ref).where();
    const image want = raycast_test::render_with(renderer(s, render_options{}), pixel_format::rgb8);
    EXPECT_EQ(f.img.bytes, want.bytes) << compare(f.img, want).where();
  }
}

// The README's gallery (tests/golden/gallery/commands.txt): each command still
// renders exactly its picture.
TEST(Golden, GalleryCommandsRenderTheirPictures) {
  std::istringstream lines(raycast_test::read_file(RAYCAST_GOLDEN_DIR "/gallery/commands.txt"));
  int checked = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(':');
    ASSERT_NE(colon, std::string::npos) << line;
    const std::string file = line.substr(0, colon);
    std::vector<std::string> args;
    std::istringstream words(line.substr(colon + 1));
    for (std::string w; words >> w;) {
      if (w.rfind("{gallery}", 0) == 0) w = RAYCAST_GOLDEN_DIR "/gallery" + w.substr(9);
      args.push_back(w);
    }
    args.insert(args.end(), {"-o", "picture.ppm"});
    cli_sandbox box;
    const run_result r = box.run(args);
    ASSERT_EQ(r.exit_code, 0) << file << ": " << r.err;
    const raycast_test::ppm p = raycast_test::parse_ppm(raycast_test::read_file(box.work() / "picture.ppm"));
    ASSERT_TRUE(p.error.empty()) << p.error;
    const read_back golden = read_image(RAYCAST_GOLDEN_DIR "/gallery/" + file, pixel_format::rgb8);
    ASSERT_TRUE(golden.error.empty()) << file << ": " << golden.error;
    ASSERT_EQ(golden.img.bytes.size(), p.pixels.size()) << file;
    EXPECT_TRUE(std::equal(p.pixels.begin(), p.pixels.end(), golden.img.bytes.begin(),
                           [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; }))
        << file << " no longer matches its command";
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

}  // namespace
