// The renderer (render.h): same bytes whatever the thread count or banding,
// backends agreeing with the double reference.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "render/render.h"
#include "backend_test.h"
#include "render_support.h"

namespace raycast {
// Backend names in test output instead of raw bytes.
void PrintTo(backend b, std::ostream* os) { *os << to_string(b); }
}  // namespace raycast

namespace {

using namespace raycast;
using raycast_test::compare;
using raycast_test::image;
using raycast_test::make_scene;
using raycast_test::render_with;

scene sized_scene(int64_t w, int64_t h) { return make_scene(raycast_test::sized(w, h)); }

// What the backend must compute, single-threaded: the reference itself, or for
// every float backend in exact mode the scalar renderer, bit for bit (scalar.h).
image direct(backend b, const scene& s, pixel_format f) {
  return b == backend::reference ? raycast_test::render_with_reference(s, f)
                                 : raycast_test::render_with_scalar(s, precision::exact, f);
}

TEST(Backends, NamesRoundTrip) {
  EXPECT_EQ(parse_backend(to_string(backend::automatic)), backend::automatic);
  for (backend b : all_backends) {
    const auto parsed = parse_backend(to_string(b));
    ASSERT_TRUE(parsed.has_value()) << to_string(b);
    EXPECT_EQ(*parsed, b);
  }
  EXPECT_EQ(parse_backend("auto"), backend::automatic);
  EXPECT_FALSE(parse_backend("nope").has_value());
  EXPECT_FALSE(parse_backend("").has_value());
  EXPECT_EQ(parse_precision("exact"), precision::exact);
  EXPECT_EQ(parse_precision("fast"), precision::fast);
  EXPECT_FALSE(parse_precision("nope").has_value());
}

TEST(Backends, AutomaticResolvesToARunnableBackend) {
  const renderer r(make_scene(), render_options{});
  EXPECT_NE(r.selected(), backend::automatic);
  EXPECT_EQ(r.selected(), best_backend());
  EXPECT_FALSE(backend_unavailable(r.selected()).has_value());
  EXPECT_EQ(r.prec(), default_precision);
  EXPECT_EQ(r.threads(), available_cores());
  EXPECT_GE(available_cores(), 1);
}

TEST(Backends, ReferenceAndScalarRunEverywhere) {
  EXPECT_FALSE(backend_unavailable(backend::reference).has_value());
  EXPECT_FALSE(backend_unavailable(backend::scalar).has_value());
}

// Every backend this machine runs; the others are skipped, and must refuse.
class RendererTest : public raycast_test::backend_test<backend> {
 protected:
  void SetUp() override {
    if (backend_unavailable(GetParam())) {
      render_options o;
      o.which = GetParam();
      EXPECT_THROW(renderer(make_scene(), o), unsupported_backend);
    }
    backend_test::SetUp();
  }
  renderer make(const scene& s, int threads) const {
    render_options o;
    o.which = GetParam();
    o.threads = threads;
    return renderer(s, o);
  }
};

TEST_P(RendererTest, SelectsTheRequestedBackend) {
  const renderer r = make(make_scene(), 3);
  EXPECT_EQ(r.selected(), GetParam());
  EXPECT_EQ(r.threads(), 3);
}

// The renderer adds bands, threads and the plan's shortcuts around a backend;
// none of it may change a byte of what the backend computes alone. (Thread
// invariance itself: test_equivalence.cpp, ThreadEquivalence.)
TEST_P(RendererTest, GivesWhatTheBackendComputesAlone) {
  for (const auto& [w, h] : {std::pair<int64_t, int64_t>{400, 225}, {37, 5}, {3, 2}}) {
    const scene s = sized_scene(w, h);
    for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
      const image want = direct(GetParam(), s, f);
      const image got = render_with(make(s, 0), f);
      EXPECT_EQ(got.bytes, want.bytes)
          << w << "x" << h << ", format " << int(f) << ": " << compare(got, want).where();
    }
  }
}

TEST_P(RendererTest, BandsEqualTheWholeImage) {
  const scene s = make_scene();
  const int64_t W = s.cam.image_width;
  ASSERT_EQ(s.cam.image_height, 225);
  for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
    for (int threads : {1, 3}) {
      const renderer r = make(s, threads);
      const image whole = render_with(r, f);
      const size_t row_bytes = size_t(W) * bytes_per_pixel(f);
      const size_t stride = row_bytes + 20;  // padding the renderer must not touch
      // Uneven bands, rendered last first.
      const std::vector<std::pair<int64_t, int64_t>> bands = {
          {0, 1}, {1, 2}, {2, 100}, {100, 101}, {101, 224}, {224, 225}};
      for (auto it = bands.rbegin(); it != bands.rend(); ++it) {
        const auto [b0, b1] = *it;
        std::vector<unsigned char> buf(stride * size_t(b1 - b0), 0xAB);
        r.render(image_band{buf.data(), stride, f, b0, b1});
        for (int64_t row = b0; row < b1; ++row) {
          const unsigned char* got = buf.data() + size_t(row - b0) * stride;
          const unsigned char* want = whole.bytes.data() + size_t(row) * row_bytes;
          ASSERT_EQ(std::vector<unsigned char>(got, got + row_bytes),
                    std::vector<unsigned char>(want, want + row_bytes))
              << "band [" << b0 << ", " << b1 << "), row " << row << ", " << threads << " threads";
          for (size_t k = row_bytes; k < stride; ++k)
            ASSERT_EQ(got[k], 0xAB) << "padding overwritten in row " << row;
        }
      }
    }
  }
}

TEST_P(RendererTest, EmptyBandWritesNothing) {
  const scene s = sized_scene(8, 8);
  const renderer r = make(s, 4);
  std::vector<unsigned char> buf(8 * 3 * 8, 0xAB);
  r.render(image_band{buf.data(), 8 * 3, pixel_format::rgb8, 5, 5});
  EXPECT_EQ(buf, std::vector<unsigned char>(buf.size(), 0xAB));
}

TEST_P(RendererTest, FloatOutputIsWithinOneMillionthOfReferencePixel) {
  for (const auto& [w, h] : {std::pair<int64_t, int64_t>{400, 225}, {1, 1}, {33, 1}, {1, 17}}) {
    const scene s = sized_scene(w, h);
    const image img = render_with(make(s, 2), pixel_format::rgb_f32);
    const auto d = raycast_test::compare_to_reference_pixels(img, s);
    EXPECT_LE(d.max, 1e-6) << w << "x" << h << ": " << d.where();
  }
}

TEST_P(RendererTest, Rgb8IsWithinOneLsbOfTheReference) {
  for (const auto& [w, h] :
       {std::pair<int64_t, int64_t>{400, 225}, {401, 225}, {1280, 720}, {2, 2}, {640, 1}, {1, 9}}) {
    const scene s = sized_scene(w, h);
    const image got = render_with(make(s, 0), pixel_format::rgb8);
    const image want = raycast_test::render_with_reference(s, pixel_format::rgb8);
    const auto d = compare(got, want);
    EXPECT_LE(d.max, 1) << w << "x" << h << ": " << d.where();
  }
}

// Cameras the CLI accepts that stress float: far origins, tiny and huge
// viewports (float_scene scales them), narrow and wide fields of view, and sky
// colours outside [0, 1] that 8-bit output clamps.
using raycast_test::scene_case;

api::camera with(double vh, double focal, point3 origin, int64_t w = 160, int64_t h = 90) {
  api::camera p;
  p.viewport_height = vh;
  p.focal_length = focal;
  p.lookfrom = origin;
  p.width = w;
  p.height = h;
  return p;
}

const scene_case camera_cases[] = {
    {"far_origin", with(2, 1, point3(1e9, -1e9, 5)), sky{}},
    {"tiny_viewport", with(1e-30, 1e-30, point3(0)), sky{}},
    {"huge_viewport", with(1e30, 1e30, point3(0)), sky{}},
    {"wide_field", with(2, 1e-3, point3(0)), sky{}},
    {"narrow_field", with(2, 1e3, point3(0)), sky{}},
    {"out_of_range_sky", with(2, 1, point3(0)), sky{color(2, -1, 0.5), color(0, 1.5, 0.25)}},
    {"reversed_sky", with(3, 0.5, point3(0)), sky{color(0.5, 0.7, 1.0), color(1, 1, 1)}},
};

TEST_P(RendererTest, Rgb8IsWithinOneLsbOfTheReferenceForOtherCameras) {
  for (const scene_case& c : camera_cases) {
    ASSERT_FALSE(validate(c.cam).has_value()) << c.name;
    const scene s = make_scene(c.cam, c.sky);
    const image got = render_with(make(s, 0), pixel_format::rgb8);
    const image want = raycast_test::render_with_reference(s, pixel_format::rgb8);
    const auto d = compare(got, want);
    EXPECT_LE(d.max, 1) << c.name << ": " << d.where();
  }
}

TEST_P(RendererTest, FastPrecisionIsWithinOneLsbOfTheReference) {
  for (const auto& [w, h] : {std::pair<int64_t, int64_t>{400, 225}, {1280, 720}, {7, 1}, {23, 3}}) {
    const scene s = sized_scene(w, h);
    render_options o;
    o.which = GetParam();
    o.prec = precision::fast;
    const renderer r(s, o);
    EXPECT_EQ(r.prec(), precision::fast);
    const auto d = compare(render_with(r, pixel_format::rgb8),
                           raycast_test::render_with_reference(s, pixel_format::rgb8));
    EXPECT_LE(d.max, 1) << w << "x" << h << ": " << d.where();
  }
}

std::string backend_name(const ::testing::TestParamInfo<backend>& p) {
  return std::string(to_string(p.param));
}

INSTANTIATE_TEST_SUITE_P(Backends, RendererTest, ::testing::ValuesIn(all_backends), backend_name);

}  // namespace
