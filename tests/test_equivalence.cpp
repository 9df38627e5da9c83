// Scalar-vs-SIMD equivalence: every backend this CPU runs x both precisions x
// many widths and heights x several cameras and skies.
//  - exact mode: byte-identical (8-bit) and bit-identical (float) to the
//    scalar float renderer;
//  - fast mode: within its documented bound (scalar.h) of the double reference;
//  - every mode: 8-bit within 1 LSB of the double reference.
// A backend the CPU lacks is skipped with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "backend_test.h"
#include "render_support.h"

namespace {

using namespace raycast;
using raycast_test::image;

using raycast_test::colour_scale;
using raycast_test::scene_case;

const std::vector<scene_case>& cameras() {
  static const std::vector<scene_case> all = [] {
  std::vector<scene_case> v;
  v.push_back({"lesson", {}, {}});
  api::camera p;
  p.viewport_height = 0.37;
  v.push_back({"viewport_0_37", p, {}});
  p = {};
  p.viewport_height = 9.0;
  p.focal_length = 0.25;
  v.push_back({"wide_viewport_short_focal", p, {}});
  p = {};
  p.focal_length = 6.5;
  v.push_back({"long_focal", p, {}});
  p = {};
  p.lookfrom = {3.0, -2.0, 7.5};
  v.push_back({"moved_origin", p, {}});
  p = {};
  p.aspect = 4.0 / 3.0;
  v.push_back({"aspect_4_3", p, {}});
  p = {};
  p.aspect = 0.5;
  v.push_back({"aspect_1_2", p, {}});
  v.push_back({"sky_black_to_white", {}, {{0, 0, 0}, {1, 1, 1}}});
  v.push_back({"sky_every_channel_varies", {}, {{0.9, 0.2, 0.05}, {0.1, 0.6, 0.95}}});
  v.push_back({"sky_hdr", {}, {{4.0, 2.0, 0.5}, {-1.0, 0.25, 16.0}}});
  return v;
  }();
  return all;
}

const std::vector<int64_t>& widths() {
  static const std::vector<int64_t> w = [] {
    std::vector<int64_t> v;
    for (int64_t i = 1; i <= 33; ++i) v.push_back(i);
    for (int64_t i : {63, 64, 65, 255, 256, 257, 400, 1920}) v.push_back(i);
    return v;
  }();
  return w;
}
const std::vector<int64_t> heights = {1, 2, 3, 225};

struct param {
  backend which;
  precision prec;
  size_t camera;
};

void PrintTo(const param& p, std::ostream* os) {
  *os << to_string(p.which) << "/" << to_string(p.prec) << "/" << cameras()[p.camera].name;
}

std::string param_name(const ::testing::TestParamInfo<param>& info) {
  return std::string(to_string(info.param.which)) + "_" + std::string(to_string(info.param.prec)) +
         "_" + cameras()[info.param.camera].name;
}

std::vector<param> all_params() {
  std::vector<param> v;
  for (backend b : target_backends)
    for (precision p : {precision::exact, precision::fast})
      for (size_t c = 0; c < cameras().size(); ++c) v.push_back({b, p, c});
  return v;
}

class Equivalence : public raycast_test::backend_test<param> {};

TEST_P(Equivalence, EveryWidthAndHeight) {
  const param& prm = GetParam();
  const scene_case& cc = cameras()[prm.camera];
  const double bound =
      error_bound(prm.prec) * colour_scale(cc.sky);
  for (int64_t h : heights) {
    for (int64_t w : widths()) {
      SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
      api::camera cp = cc.cam;
      cp.width = w;
      cp.height = h;
      const scene s = raycast_test::make_scene(cp, cc.sky);
      const renderer r(s, {prm.which, prm.prec, 1});
      const image got8 = raycast_test::render_with(r, pixel_format::rgb8);
      const image gotf = raycast_test::render_with(r, pixel_format::rgb_f32);
      if (prm.which != backend::scalar && prm.prec == precision::exact) {
        // The general path (no shortcut: every lane, every channel, every
        // clamp), and each shortcut alone, give the same bits as every
        // shortcut the scene allows.
        for (unsigned shortcuts : {shortcut::none, shortcut::lanes, shortcut::channels,
                                   shortcut::clamps, shortcut::lanes | shortcut::mirror}) {
          render_options o{prm.which, prm.prec, 1};
          o.shortcuts = shortcuts;
          const renderer g(s, o);
          ASSERT_EQ(got8.bytes, raycast_test::render_with(g, pixel_format::rgb8).bytes)
              << "shortcuts " << shortcuts << " differ from taking them all (8-bit)";
          ASSERT_EQ(gotf.bytes, raycast_test::render_with(g, pixel_format::rgb_f32).bytes)
              << "shortcuts " << shortcuts << " differ from taking them all (float)";
        }
      }
      if (prm.prec == precision::exact) {
        const image want8 = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb8);
        const image wantf = raycast_test::render_with_scalar(s, precision::exact, pixel_format::rgb_f32);
        ASSERT_EQ(got8.bytes, want8.bytes) << raycast_test::compare(got8, want8).where();
        ASSERT_EQ(0, std::memcmp(gotf.bytes.data(), wantf.bytes.data(), gotf.bytes.size()))
            << "float output is not bit-identical to the scalar renderer: "
            << raycast_test::compare(gotf, wantf).where();
      }
      const raycast_test::difference df = raycast_test::compare_to_reference_pixels(gotf, s);
      ASSERT_LE(df.max, bound) << df.where();
      const image ref8 = raycast_test::render_with_reference(s, pixel_format::rgb8);
      const raycast_test::difference d8 = raycast_test::compare(got8, ref8);
      ASSERT_LE(d8.max, 1.0) << d8.where();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Equivalence, ::testing::ValuesIn(all_params()), param_name);

// Threads split the image into bands of rows; the bytes must not depend on
// how. The one test of thread invariance: large enough that every thread
// gets rows (a job under 2^17 pixels per thread stays on one), and, with
// images of fewer rows than threads, small enough that some get none.
class ThreadEquivalence : public raycast_test::backend_test<backend> {};

TEST_P(ThreadEquivalence, AnyThreadCountGivesTheSameBytes) {
  for (const auto& [w, h] : {std::pair<int64_t, int64_t>{1031, 1000}, {65536, 5}, {3, 2}}) {
    const scene s = raycast_test::make_scene(raycast_test::sized(w, h));
    for (precision p : {precision::exact, precision::fast}) {
      for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
        const image one = raycast_test::render_with(renderer(s, {GetParam(), p, 1}), f);
        for (int t : {2, 3, 7}) {
          const image many = raycast_test::render_with(renderer(s, {GetParam(), p, t}), f);
          ASSERT_EQ(one.bytes, many.bytes) << w << "x" << h << ", " << t << " threads, " << to_string(p);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, ThreadEquivalence,
                         ::testing::ValuesIn(target_backends),
                         [](const ::testing::TestParamInfo<backend>& i) {
                           return std::string(to_string(i.param));
                         });

// The kernel writes exactly W x 3 bytes (or floats) per row: nothing before or
// after a row's pixels changes, at every tail length, even with a row stride
// wider than the row.
class Tails : public raycast_test::backend_test<backend> {};

TEST_P(Tails, NoByteOutsideTheRowIsWritten) {
  for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
    for (int64_t w = 1; w <= 40; ++w) {
      api::camera cp;
      cp.width = w;
      cp.height = 3;
      const scene s = raycast_test::make_scene(cp);
      const size_t row = size_t(w) * bytes_per_pixel(f), pad = 64, stride = row + 2 * pad;
      std::vector<unsigned char> buf(stride * 3 + 2 * pad, 0xA5);
      const renderer r(s, {GetParam(), precision::exact, 1});
      r.render({buf.data() + pad, stride, f, 0, 3});
      for (size_t k = 0; k < buf.size(); ++k) {
        const size_t off = k < pad ? stride : (k - pad) % stride;
        if (k < pad || off >= row) {
          ASSERT_EQ(buf[k], 0xA5) << "byte " << k << " written, width " << w;
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Tails,
                         ::testing::ValuesIn(simd_backends),
                         [](const ::testing::TestParamInfo<backend>& i) {
                           return std::string(to_string(i.param));
                         });

}  // namespace
