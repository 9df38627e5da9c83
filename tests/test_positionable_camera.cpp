// The book's positionable camera (--lookfrom/--lookat/--vup/--vfov) against an
// independent double-precision implementation written here from the book's
// formulas, on every backend and precision; degenerate cameras are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "backend_test.h"
#include "render_support.h"

namespace {

using namespace raycast;
using raycast_test::image;

struct book_camera {
  point3 lookfrom, lookat;
  vec3 vup;
  double vfov_degrees, aspect, focal;
};

struct v3 {
  double x, y, z;
};
v3 sub(v3 a, v3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
v3 add(v3 a, v3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
v3 mul(double s, v3 a) { return {s * a.x, s * a.y, s * a.z}; }
v3 cross(v3 a, v3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
v3 unit(v3 a) { return mul(1.0 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z), a); }

// Ray Tracing in One Weekend, "Positionable camera", then the lesson's sky.
v3 book_pixel(const book_camera& c, int64_t W, int64_t H, int64_t i, int64_t j) {
  const double h = std::tan(c.vfov_degrees * std::numbers::pi / 180.0 / 2.0);
  const double viewport_height = 2.0 * h * c.focal;
  const double viewport_width = c.aspect * viewport_height;
  const v3 from{c.lookfrom.x, c.lookfrom.y, c.lookfrom.z}, at{c.lookat.x, c.lookat.y, c.lookat.z};
  const v3 w = unit(sub(from, at));
  const v3 u = unit(cross({c.vup.x, c.vup.y, c.vup.z}, w));
  const v3 v = cross(w, u);
  const v3 horizontal = mul(viewport_width, u), vertical = mul(viewport_height, v);
  // Relative to lookfrom: the sky depends on the direction only.
  const v3 corner = sub(sub(mul(-0.5, horizontal), mul(0.5, vertical)), mul(c.focal, w));
  const double s = W == 1 ? 0.5 : double(i) / double(W - 1);
  const double t = H == 1 ? 0.5 : double(j) / double(H - 1);
  const v3 dir = unit(add(add(corner, mul(s, horizontal)), mul(t, vertical)));
  const double k = 0.5 * (dir.y + 1.0);
  return add(mul(1.0 - k, {1.0, 1.0, 1.0}), mul(k, {0.5, 0.7, 1.0}));
}

struct named_camera {
  std::string name;
  book_camera cam;
};

std::vector<named_camera> cameras() {
  const vec3 up(0, 1, 0);
  return {
      {"tilted_horizon", {{0, 0, 0}, {0, 0, -1}, {0.3, 1, 0}, 90, 16.0 / 9.0, 1}},
      {"looking_up", {{0, 0, 0}, {0, 1, -0.3}, up, 90, 16.0 / 9.0, 1}},
      {"looking_down_and_along_x", {{0, 0, 0}, {1, -0.4, 0.2}, up, 60, 16.0 / 9.0, 2}},
      {"wide_fov", {{0, 0, 0}, {0, 0, -1}, up, 150, 2.0, 1}},
      {"narrow_fov", {{0, 0, 0}, {0.2, 0.1, -1}, up, 2, 1.0, 1}},
      {"far_lookfrom", {{1e12, 1e12, 1e12}, {1e12, 1e12 + 1, 1e12 - 1}, up, 70, 16.0 / 9.0, 1}},
      {"upside_down", {{0, 0, 0}, {0, 0, -1}, {0, -1, 0}, 90, 16.0 / 9.0, 1}},
  };
}

api::camera to_params(const book_camera& c, int64_t W, int64_t H) {
  api::camera p;
  p.width = W;
  p.height = H;
  p.aspect = c.aspect;
  p.focal_length = c.focal;
  p.lookfrom = c.lookfrom;
  p.lookat = c.lookat;
  p.vup = c.vup;
  p.vfov = c.vfov_degrees;
  return p;
}

using raycast_test::mode;

class PositionableCamera : public raycast_test::backend_test<mode> {};

TEST_P(PositionableCamera, MatchesTheBooksCameraComputedIndependently) {
  for (const named_camera& nc : cameras()) {
    SCOPED_TRACE(nc.name);
    for (auto [W, H] : {std::pair<int64_t, int64_t>{67, 31}, {400, 225}, {1, 1}}) {
      const scene s = raycast_test::make_scene(to_params(nc.cam, W, H));
      const renderer r(s, {GetParam().which, GetParam().prec, 1});
      const image f = raycast_test::render_with(r, pixel_format::rgb_f32);
      const image b = raycast_test::render_with(r, pixel_format::rgb8);
      const double bound = GetParam().which == backend::reference ? 1e-6
                           : GetParam().prec == precision::exact ? exact_error_bound
                                                                 : fast_error_bound;
      double worst = 0;
      for (int64_t row = 0; row < H; ++row)
        for (int64_t i = 0; i < W; ++i) {
          const v3 want = book_pixel(nc.cam, W, H, i, H - 1 - row);
          const double wk[3] = {want.x, want.y, want.z};
          for (int k = 0; k < 3; ++k) {
            worst = std::max(worst, std::abs(double(f.value(row, i, k)) - wk[k]));
            const int byte = int(255.999 * std::clamp(wk[k], 0.0, 1.0));
            ASSERT_LE(std::abs(b.byte(row, i, k) - byte), 1)
                << W << "x" << H << " row " << row << " col " << i;
          }
        }
      EXPECT_LE(worst, bound) << W << "x" << H;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, PositionableCamera, ::testing::ValuesIn(raycast_test::all_modes()),
                         raycast_test::mode_name);

// In exact mode a tilted camera runs the general kernel path on every SIMD
// backend and still gives the scalar float renderer's bits.
class TiltedCamera : public raycast_test::backend_test<backend> {};

TEST_P(TiltedCamera, ExactModeIsBitIdenticalToTheScalarRenderer) {
  const backend b = GetParam();
  for (const named_camera& nc : cameras()) {
    const scene s = raycast_test::make_scene(to_params(nc.cam, 131, 37));
    for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32})
      EXPECT_EQ(raycast_test::render_with(renderer(s, {b, precision::exact, 1}), f).bytes,
                raycast_test::render_with_scalar(s, precision::exact, f).bytes)
          << to_string(b) << " " << nc.name;
  }
}

INSTANTIATE_TEST_SUITE_P(SimdBackends, TiltedCamera, ::testing::ValuesIn(simd_backends),
                         raycast_test::backend_name);

TEST(PositionableCamera, WithoutItsOptionsTheCameraIsTheLessons) {
  const camera lesson = make_camera({});
  api::camera p;
  p.lookat = point3(0, 0, -1);  // the lesson's own view, spelled out
  const camera spelled = make_camera(p);
  EXPECT_EQ(lesson.horizontal, spelled.horizontal);
  EXPECT_EQ(lesson.vertical, spelled.vertical);
  EXPECT_EQ(lesson.corner_dir, spelled.corner_dir);
  EXPECT_EQ(lesson.horizontal, vec3(16.0 / 9.0 * 2.0, 0, 0));
}

TEST(PositionableCamera, VfovSetsTheViewportHeight) {
  api::camera p;
  p.vfov = 90.0;
  p.focal_length = 3.0;
  EXPECT_NEAR(make_camera(p).viewport_height, 6.0, 1e-12);  // 2 tan(45 deg) 3
}

TEST(PositionableCamera, FarLookfromIsTheSameImageAsNearOrigin) {
  api::camera near = to_params(cameras()[5].cam, 64, 36), far = near;
  near.lookfrom = point3(0, 0, 0);
  near.lookat = point3(0, 1, -1);
  for (backend b : target_backends) {
    if (backend_unavailable(b)) continue;
    EXPECT_EQ(raycast_test::render_with(renderer(raycast_test::make_scene(near), {b}), pixel_format::rgb_f32).bytes,
              raycast_test::render_with(renderer(raycast_test::make_scene(far), {b}), pixel_format::rgb_f32).bytes)
        << to_string(b);
  }
}

TEST(PositionableCamera, DegenerateCamerasAreRefused) {
  api::camera same;
  same.lookat = point3(0, 0, 0);
  EXPECT_TRUE(validate(same).has_value());
  api::camera parallel;
  parallel.lookat = point3(0, 5, 0);  // looking straight up with vup = +y
  EXPECT_TRUE(validate(parallel).has_value());
  api::camera zero_up;
  zero_up.lookat = point3(0, 0, -1);
  zero_up.vup = vec3(0);
  EXPECT_TRUE(validate(zero_up).has_value());
  for (double f : {0.0, -10.0, 180.0, 200.0, double(NAN)}) {
    api::camera fov;
    fov.vfov = f;
    EXPECT_TRUE(validate(fov).has_value()) << f;
  }
  api::camera ok;
  ok.lookat = point3(0, 5, -0.001);
  EXPECT_FALSE(validate(ok).has_value());
}

}  // namespace
