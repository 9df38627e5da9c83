// The camera, rays, the sky colour and 8-bit quantization, checked against
// The lesson's formulas and check values (src/scene/README.md), and against the lesson's own loop.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "reference/color.h"
#include "prepare/float_scene.h"
#include "reference/reference.h"
#include "render_support.h"
#include "kernels/scalar.h"

namespace {

using namespace raycast;
using raycast_test::image;
using raycast_test::make_scene;

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_v = std::numeric_limits<double>::infinity();

void expect_vec_eq(const vec3& got, const vec3& want) {
  EXPECT_EQ(got.x, want.x);
  EXPECT_EQ(got.y, want.y);
  EXPECT_EQ(got.z, want.z);
}

// ---------------------------------------------------------------- camera

TEST(Camera, DefaultsAreTheLessonsCamera) {
  const api::camera p;
  ASSERT_FALSE(validate(p).has_value());
  const camera c = make_camera(p);
  EXPECT_EQ(c.image_width, 400);
  EXPECT_EQ(c.image_height, 225);
  EXPECT_EQ(c.aspect_ratio, 16.0 / 9.0);
  EXPECT_EQ(c.viewport_height, 2.0);
  EXPECT_EQ(c.viewport_width, 16.0 / 9.0 * 2.0);
  EXPECT_EQ(c.focal_length, 1.0);
  expect_vec_eq(c.origin, vec3(0, 0, 0));
  expect_vec_eq(c.horizontal, vec3(16.0 / 9.0 * 2.0, 0, 0));
  expect_vec_eq(c.vertical, vec3(0, 2, 0));
  expect_vec_eq(c.lower_left_corner, vec3(-16.0 / 9.0, -1, -1));
}

TEST(Camera, QuantitiesFollowTheParameters) {
  api::camera p;
  p.aspect = 2.5;
  p.width = 250;
  p.viewport_height = 3.0;
  p.focal_length = 0.5;
  p.lookfrom = point3(10, -20, 30);
  ASSERT_FALSE(validate(p).has_value());
  const camera c = make_camera(p);
  EXPECT_EQ(c.image_height, 100);
  EXPECT_EQ(c.viewport_width, 7.5);
  expect_vec_eq(c.horizontal, vec3(7.5, 0, 0));
  expect_vec_eq(c.vertical, vec3(0, 3, 0));
  // origin - horizontal/2 - vertical/2 - (0, 0, focal)
  expect_vec_eq(c.lower_left_corner, vec3(10 - 3.75, -20 - 1.5, 30 - 0.5));
  expect_vec_eq(c.corner_dir, vec3(-3.75, -1.5, -0.5));
}

TEST(Camera, ViewportWidthIsIdealAspectTimesViewportHeightNotPixelRatio) {
  api::camera p;
  p.width = 400;
  p.height = 100;  // pixel ratio 4, aspect stays 16/9
  const camera c = make_camera(p);
  EXPECT_EQ(c.image_height, 100);
  EXPECT_EQ(c.viewport_width, 16.0 / 9.0 * 2.0);
  expect_vec_eq(c.horizontal, vec3(16.0 / 9.0 * 2.0, 0, 0));
}

TEST(Camera, DefaultHeightIsIntOfWidthOverAspect) {
  EXPECT_EQ(default_height(400, 16.0 / 9.0), 225);
  EXPECT_EQ(default_height(401, 16.0 / 9.0), 225);  // 225.56 truncated
  EXPECT_EQ(default_height(100, 1.0), 100);
  EXPECT_EQ(default_height(3, 0.5), 6);
  EXPECT_EQ(default_height(1920, 16.0 / 9.0), 1080);
}

TEST(Camera, DefaultHeightNeverBelowOneForVeryWideAspects) {
  EXPECT_EQ(default_height(1, 2.0), 1);        // 0.5
  EXPECT_EQ(default_height(10, 1000.0), 1);    // 0.01
  EXPECT_EQ(default_height(400, 1e300), 1);
  api::camera p;
  p.width = 10;
  p.aspect = 1000.0;
  ASSERT_FALSE(validate(p).has_value());
  EXPECT_EQ(make_camera(p).image_height, 1);
}

TEST(Camera, ExplicitHeightOverridesDefault) {
  api::camera p;
  p.height = 17;
  EXPECT_EQ(make_camera(p).image_height, 17);
}

struct refusal {
  const char* name;
  void (*change)(api::camera&);
  const char* mentions;  // the message names the parameter
};

class CameraValidate : public ::testing::TestWithParam<refusal> {};

TEST_P(CameraValidate, RefusesWithMessageNamingTheParameter) {
  api::camera p;
  GetParam().change(p);
  const auto why = validate(p);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->message.find(GetParam().mentions), std::string::npos) << why->message;
}

const refusal refusals[] = {
    {"aspect_nan", [](api::camera& p) { p.aspect = nan_v; }, "aspect"},
    {"aspect_inf", [](api::camera& p) { p.aspect = inf_v; }, "aspect"},
    {"aspect_zero", [](api::camera& p) { p.aspect = 0.0; }, "aspect"},
    {"aspect_negative", [](api::camera& p) { p.aspect = -1.0; }, "aspect"},
    {"viewport_nan", [](api::camera& p) { p.viewport_height = nan_v; }, "viewport height"},
    {"viewport_inf", [](api::camera& p) { p.viewport_height = inf_v; }, "viewport height"},
    {"viewport_zero", [](api::camera& p) { p.viewport_height = 0.0; }, "viewport height"},
    {"viewport_negative", [](api::camera& p) { p.viewport_height = -2.0; }, "viewport height"},
    {"focal_nan", [](api::camera& p) { p.focal_length = nan_v; }, "focal length"},
    {"focal_inf", [](api::camera& p) { p.focal_length = -inf_v; }, "focal length"},
    {"focal_zero", [](api::camera& p) { p.focal_length = 0.0; }, "focal length"},
    {"focal_negative", [](api::camera& p) { p.focal_length = -1.0; }, "focal length"},
    {"viewport_width_overflow",
     [](api::camera& p) {
       p.aspect = 1e200;
       p.viewport_height = 1e200;
       p.height = 1;
     },
     "viewport width"},
    {"origin_nan", [](api::camera& p) { p.lookfrom = point3(0, nan_v, 0); }, "origin"},
    {"origin_inf", [](api::camera& p) { p.lookfrom = point3(0, 0, inf_v); }, "origin"},
    {"width_zero", [](api::camera& p) { p.width = 0; }, "width"},
    {"width_negative", [](api::camera& p) { p.width = -5; }, "width"},
    {"width_over_max", [](api::camera& p) { p.width = max_dimension + 1; }, "width"},
    {"height_zero", [](api::camera& p) { p.height = 0; }, "height"},
    {"height_negative", [](api::camera& p) { p.height = -3; }, "height"},
    {"height_over_max", [](api::camera& p) { p.height = max_dimension + 1; }, "height"},
    {"default_height_over_max",
     [](api::camera& p) {
       p.width = max_dimension;
       p.aspect = 0.5;  // height 2^25
     },
     "height"},
};

std::string refusal_name(const ::testing::TestParamInfo<refusal>& p) { return p.param.name; }

INSTANTIATE_TEST_SUITE_P(Refusals, CameraValidate, ::testing::ValuesIn(refusals), refusal_name);

// The field to blame comes as data (the CLI maps it to an option), and a
// height derived from width / aspect blames the aspect.
TEST(SceneValidate, NamesTheFieldToBlame) {
  const auto field_of = [](auto change) {
    api::scene p;
    change(p);
    const auto e = validate(p);
    return e ? std::string(to_string(e->field)) : std::string("(valid)");
  };
  EXPECT_EQ(field_of([](api::scene&) {}), "(valid)");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.width = 0; }), "camera.width");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.height = 0; }), "camera.height");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.aspect = 1e-9; }), "camera.aspect");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.vfov = 180.0; }), "camera.vfov");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.lookat = p.cam.lookfrom; }), "camera.lookat");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.lookat = point3(0, 5, 0); }), "camera.vup");
  EXPECT_EQ(field_of([](api::scene& p) { p.cam.lookfrom.x = inf_v; }), "camera.lookfrom");
  EXPECT_EQ(field_of([](api::scene& p) { p.sky.bottom.y = nan_v; }), "sky.bottom");
  EXPECT_EQ(field_of([](api::scene& p) { p.sky.top.z = 1e31; }), "sky.top");
}

TEST(Camera, ValidateAcceptsTheLimitsThemselves) {
  api::camera p;
  p.width = max_dimension;  // default height 9437184, under the limit
  EXPECT_FALSE(validate(p).has_value());
  p.width = 1;
  p.height = max_dimension;
  EXPECT_FALSE(validate(p).has_value());
  api::camera tiny;
  tiny.viewport_height = 1e-300;
  tiny.focal_length = 1e-300;
  tiny.lookfrom = point3(-1e300, 1e300, 0);
  EXPECT_FALSE(validate(tiny).has_value());
}

TEST(Camera, PixelCoordinatesAreIOverWMinus1AndJOverHMinus1) {
  const camera c = make_camera(api::camera{});
  EXPECT_EQ(c.u_of(0), 0.0);
  EXPECT_EQ(c.u_of(399), 1.0);
  EXPECT_EQ(c.u_of(133), 133.0 / 399.0);
  EXPECT_EQ(c.v_of(0), 0.0);
  EXPECT_EQ(c.v_of(224), 1.0);
  EXPECT_EQ(c.v_of(112), 0.5);
}

// ---------------------------------------------------------------- ray

TEST(Ray, AtIsOriginPlusTTimesDirection) {
  const ray r(point3(1, 2, 3), vec3(4, 5, 6));
  expect_vec_eq(r.origin(), point3(1, 2, 3));
  expect_vec_eq(r.direction(), vec3(4, 5, 6));
  expect_vec_eq(r.at(0.0), point3(1, 2, 3));
  expect_vec_eq(r.at(1.0), point3(5, 7, 9));
  expect_vec_eq(r.at(2.5), point3(11, 14.5, 18));
  expect_vec_eq(r.at(-0.5), point3(-1, -0.5, 0));
}

TEST(Ray, GetRayGoesThroughTheViewportPoint) {
  api::camera p;
  p.lookfrom = point3(1, 2, 3);
  const camera c = make_camera(p);
  const ray r = c.get_ray(0.25, 0.75);
  expect_vec_eq(r.origin(), to_glm(p.lookfrom));
  const point3 on_viewport = c.lower_left_corner + 0.25 * c.horizontal + 0.75 * c.vertical;
  const point3 hit = r.at(1.0);
  EXPECT_DOUBLE_EQ(hit.x, on_viewport.x);
  EXPECT_DOUBLE_EQ(hit.y, on_viewport.y);
  EXPECT_DOUBLE_EQ(hit.z, on_viewport.z);
}

// ---------------------------------------------------------------- colour

TEST(RayColor, StraightUpIsExactlyTheTopColour) {
  for (double len : {1.0, 5.0, 1e-300, 1e300}) {
    const color c = ray_color(ray(point3(0), vec3(0, len, 0)), sky{});
    EXPECT_EQ(c.r, 0.5) << len;
    EXPECT_EQ(c.g, 0.7) << len;
    EXPECT_EQ(c.b, 1.0) << len;
  }
}

TEST(RayColor, StraightDownIsExactlyWhite) {
  for (double len : {1.0, 0.25, 1e-300, 1e300}) {
    const color c = ray_color(ray(point3(0), vec3(0, -len, 0)), sky{});
    EXPECT_EQ(c.r, 1.0) << len;
    EXPECT_EQ(c.g, 1.0) << len;
    EXPECT_EQ(c.b, 1.0) << len;
  }
}

TEST(RayColor, HorizontalIsHalfway) {
  for (const vec3& d : {vec3(1, 0, 0), vec3(0, 0, -1), vec3(-3, 0, 7), vec3(1e300, 0, 1e300)}) {
    const color c = ray_color(ray(point3(0), d), sky{});
    EXPECT_DOUBLE_EQ(c.r, 0.75);
    EXPECT_DOUBLE_EQ(c.g, 0.85);
    EXPECT_EQ(c.b, 1.0);
  }
}

TEST(RayColor, OriginDoesNotChangeTheSky) {
  const vec3 d(-16.0 / 9.0, 1, -1);
  const color at_zero = ray_color(ray(point3(0), d), sky{});
  const color far_away = ray_color(ray(point3(1e12, -7, 3e5), d), sky{});
  expect_vec_eq(far_away, at_zero);
}

TEST(RayColor, CustomSkyEndsAreReached) {
  const sky s{color(0.1, 0.2, 0.3), color(0.9, 0.8, 0.7)};
  expect_vec_eq(ray_color(ray(point3(0), vec3(0, 1, 0)), s), s.top);
  expect_vec_eq(ray_color(ray(point3(0), vec3(0, -1, 0)), s), s.bottom);
}

TEST(ToByte, TheLessonsMappingTruncates) {
  EXPECT_EQ(to_byte(0.0), 0);
  EXPECT_EQ(to_byte(0.5), 127);   // 127.9995
  EXPECT_EQ(to_byte(0.75), 191);  // 191.99925: truncated, not rounded
  EXPECT_EQ(to_byte(0.85), 217);
  for (int k = 0; k <= 255; ++k) EXPECT_EQ(to_byte(k / 255.0), k) << k;
}

TEST(ToByte, OneIs255AndNothingWraps) {
  EXPECT_EQ(to_byte(1.0), 255);
  EXPECT_EQ(to_byte(std::nextafter(1.0, 2.0)), 255);
  EXPECT_EQ(to_byte(1.00001), 255);  // 256.0016 unclamped: would wrap to 0
  EXPECT_EQ(to_byte(1.5), 255);
  EXPECT_EQ(to_byte(1e300), 255);
  EXPECT_EQ(to_byte(inf_v), 255);
}

TEST(ToByte, NegativeIsZero) {
  EXPECT_EQ(to_byte(-0.0), 0);
  EXPECT_EQ(to_byte(-1e-12), 0);
  EXPECT_EQ(to_byte(-0.5), 0);
  EXPECT_EQ(to_byte(-1.0), 0);  // unclamped -255.999 would wrap to 1
  EXPECT_EQ(to_byte(-inf_v), 0);
}

// ---------------------------------------------------------------- check pixels

void expect_rgb(const image& img, int64_t row, int64_t col, int r, int g, int b) {
  EXPECT_EQ(img.byte(row, col, 0), r) << "row " << row << " col " << col;
  EXPECT_EQ(img.byte(row, col, 1), g) << "row " << row << " col " << col;
  EXPECT_EQ(img.byte(row, col, 2), b) << "row " << row << " col " << col;
}

TEST(CheckPixels, DefaultImageCornersAreExact) {
  const scene s = make_scene();
  const image img = raycast_test::render_with_reference(s, pixel_format::rgb8);
  ASSERT_EQ(img.width, 400);
  ASSERT_EQ(img.height, 225);
  // Rows top first: output row r is j = H - 1 - r.
  expect_rgb(img, 0, 0, 163, 200, 255);     // i = 0, j = 224
  expect_rgb(img, 224, 399, 220, 234, 255);  // i = 399, j = 0
}

TEST(CheckPixels, DirectionsAndTMatchSpec) {
  const scene s = make_scene();
  const camera& c = s.cam;
  expect_vec_eq(c.get_ray(c.u_of(0), c.v_of(224)).direction(), vec3(-16.0 / 9.0, 1, -1));
  expect_vec_eq(c.get_ray(c.u_of(399), c.v_of(0)).direction(), vec3(16.0 / 9.0, -1, -1));
  // red = (1 - t) * 1 + t * 0.5, so t = 2 (1 - red)
  EXPECT_NEAR(2 * (1 - reference_pixel(s, 0, 224).r), 0.720102, 1e-6);
  EXPECT_NEAR(2 * (1 - reference_pixel(s, 399, 0).r), 0.279898, 1e-6);
}

TEST(CheckPixels, ExactCentreOfAnOddImage) {
  api::camera p;
  p.width = 401;  // default height int(401 / (16/9)) = 225
  const scene s = make_scene(p);
  ASSERT_EQ(s.cam.image_height, 225);
  ASSERT_EQ(s.cam.u_of(200), 0.5);
  ASSERT_EQ(s.cam.v_of(112), 0.5);
  expect_vec_eq(s.cam.get_ray(0.5, 0.5).direction(), vec3(0, 0, -1));
  const color c = reference_pixel(s, 200, 112);
  EXPECT_DOUBLE_EQ(c.r, 0.75);
  EXPECT_DOUBLE_EQ(c.g, 0.85);
  EXPECT_EQ(c.b, 1.0);
  const image img = raycast_test::render_with_reference(s, pixel_format::rgb8);
  expect_rgb(img, 224 - 112, 200, 191, 217, 255);
  const image fimg = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb8);
  expect_rgb(fimg, 224 - 112, 200, 191, 217, 255);
}

// ---------------------------------------------------------------- degenerate sizes

class OnePixelWideOrTall : public ::testing::TestWithParam<std::pair<int64_t, int64_t>> {};

TEST_P(OnePixelWideOrTall, UsesTheCentreAndStaysFinite) {
  api::camera p;
  p.width = GetParam().first;
  p.height = GetParam().second;
  ASSERT_FALSE(validate(p).has_value());
  const scene s = make_scene(p);
  if (p.width == 1) {
    EXPECT_EQ(s.cam.u_of(0), 0.5);
  }
  if (p.height == 1) {
    EXPECT_EQ(s.cam.v_of(0), 0.5);
  }

  const image ref8 = raycast_test::render_with_reference(s, pixel_format::rgb8);
  const image ref32 = raycast_test::render_with_reference(s, pixel_format::rgb_f32);
  const image sc8 = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb8);
  const image sc32 = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb_f32);
  for (int64_t r = 0; r < s.cam.image_height; ++r)
    for (int64_t i = 0; i < s.cam.image_width; ++i) {
      const color c = reference_pixel(s, i, s.cam.image_height - 1 - r);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(std::isfinite(c[k]));
        ASSERT_TRUE(std::isfinite(ref32.value(r, i, k)));
        ASSERT_TRUE(std::isfinite(sc32.value(r, i, k)));
        EXPECT_EQ(ref8.byte(r, i, k), to_byte(c[k]));
        EXPECT_NEAR(sc8.byte(r, i, k), ref8.byte(r, i, k), 1);
      }
    }
  // The centre row (H == 1: every pixel looks horizontally) or the centre
  // column's middle pixel is the halfway colour.
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  if (H == 1) {
    for (int64_t i = 0; i < W; ++i) expect_rgb(ref8, 0, i, 191, 217, 255);
  }
  if (W == 1 && H % 2 == 1) expect_rgb(ref8, H / 2, 0, 191, 217, 255);
}

std::string size_name(const ::testing::TestParamInfo<std::pair<int64_t, int64_t>>& p) {
  return std::to_string(p.param.first) + "x" + std::to_string(p.param.second);
}

INSTANTIATE_TEST_SUITE_P(Sizes, OnePixelWideOrTall,
                         ::testing::Values(std::pair<int64_t, int64_t>{1, 1},
                                           std::pair<int64_t, int64_t>{1, 5},
                                           std::pair<int64_t, int64_t>{7, 1}),
                         size_name);

// ---------------------------------------------------------------- the lesson, independently

// The lesson's main loop as the book writes it, in double, with its own tiny
// vector type: no code from raycast. Returns rows top first (j = H-1 first).
struct lesson_vec3 {
  double x, y, z;
};
lesson_vec3 operator+(lesson_vec3 a, lesson_vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
lesson_vec3 operator-(lesson_vec3 a, lesson_vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
lesson_vec3 operator*(double t, lesson_vec3 v) { return {t * v.x, t * v.y, t * v.z}; }
lesson_vec3 operator/(lesson_vec3 v, double t) { return (1 / t) * v; }

struct lesson_image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

lesson_image lesson_render() {
  const auto aspect_ratio = 16.0 / 9.0;
  const int image_width = 400;
  const int image_height = static_cast<int>(image_width / aspect_ratio);

  const auto viewport_height = 2.0;
  const auto viewport_width = aspect_ratio * viewport_height;
  const auto focal_length = 1.0;

  const lesson_vec3 origin{0, 0, 0};
  const lesson_vec3 horizontal{viewport_width, 0, 0};
  const lesson_vec3 vertical{0, viewport_height, 0};
  const lesson_vec3 lower_left_corner =
      origin - horizontal / 2 - vertical / 2 - lesson_vec3{0, 0, focal_length};

  lesson_image out{image_width, image_height, {}};
  for (int j = image_height - 1; j >= 0; --j) {
    for (int i = 0; i < image_width; ++i) {
      const auto u = double(i) / (image_width - 1);
      const auto v = double(j) / (image_height - 1);
      const lesson_vec3 dir = lower_left_corner + u * horizontal + v * vertical - origin;
      const double length = std::sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
      const lesson_vec3 unit_direction = dir / length;
      const auto t = 0.5 * (unit_direction.y + 1.0);
      const lesson_vec3 pixel_color = (1.0 - t) * lesson_vec3{1.0, 1.0, 1.0} + t * lesson_vec3{0.5, 0.7, 1.0};
      for (double ch : {pixel_color.x, pixel_color.y, pixel_color.z})
        out.rgb.push_back(static_cast<unsigned char>(static_cast<int>(255.999 * ch)));
    }
  }
  return out;
}

void expect_within_one_lsb_of_lesson(const image& img, const lesson_image& lesson) {
  ASSERT_EQ(img.width, lesson.width);
  ASSERT_EQ(img.height, lesson.height);
  ASSERT_EQ(img.bytes.size(), lesson.rgb.size());
  int worst = 0;
  size_t worst_at = 0;
  for (size_t k = 0; k < img.bytes.size(); ++k) {
    const int d = std::abs(int(img.bytes[k]) - int(lesson.rgb[k]));
    if (d > worst) {
      worst = d;
      worst_at = k;
    }
  }
  EXPECT_LE(worst, 1) << "byte " << worst_at << " (row " << worst_at / (3 * 400) << ", column "
                      << worst_at % (3 * 400) / 3 << ")";
  // The three check pixels exactly: the lesson's, and the image's.
  const auto at = [&](const std::vector<unsigned char>& b, int row, int col, int k) {
    return int(b[size_t(row) * 1200 + size_t(col) * 3 + size_t(k)]);
  };
  const int want[2][5] = {{0, 0, 163, 200, 255}, {224, 399, 220, 234, 255}};
  for (const auto& w : want)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(at(lesson.rgb, w[0], w[1], k), w[2 + k]);
      EXPECT_EQ(at(img.bytes, w[0], w[1], k), w[2 + k]);
    }
}

TEST(Lesson, ReferenceRenderIsWithinOneLsbOfTheLessonsLoop) {
  const lesson_image lesson = lesson_render();
  ASSERT_EQ(lesson.height, 225);
  expect_within_one_lsb_of_lesson(raycast_test::render_with_reference(make_scene(), pixel_format::rgb8),
                                  lesson);
}

TEST(Lesson, FloatRenderIsWithinOneLsbOfTheLessonsLoop) {
  const lesson_image lesson = lesson_render();
  expect_within_one_lsb_of_lesson(
      raycast_test::render_with_scalar(make_scene(), precision::exact, pixel_format::rgb8), lesson);
}

}  // namespace
