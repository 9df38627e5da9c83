// Numerical stability on stiff and extreme cases (src/kernels/README.md, "The sky: numerics contract"), each
// over every backend this CPU runs x both precisions:
//   degenerate sizes, scale, far origin, exact directions, FTZ/DAZ, 64-bit
//   indexing and size limits, HDR colours, and the documented error bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "backend_test.h"
#include "render_support.h"
#include "stiff_cases.h"

namespace {

using namespace raycast;
using raycast_test::image;

using raycast_test::colour_scale;
using raycast_test::mode;
using raycast_test::stiff_case;
using raycast_test::stiff_cases;

class Numerics : public raycast_test::backend_test<mode> {
 protected:
  double bound(const raycast::sky& s) const {
    if (GetParam().which == backend::reference)  // a double render rounded to float
      return 1.2e-7 * colour_scale(s);
    return (GetParam().prec == precision::exact ? exact_error_bound : fast_error_bound) *
           colour_scale(s);
  }

  image render(const scene& s, pixel_format f, int threads = 1) const {
    return raycast_test::render_with(renderer(s, {GetParam().which, GetParam().prec, threads}), f);
  }

  // No NaN or infinity, every channel inside [min(bottom, top), max(bottom, top)]
  // of the float sky, float output within the bound of the double reference
  // and 8-bit within 1 LSB of it.
  void expect_like_reference(const scene& s) const {
    const image f = render(s, pixel_format::rgb_f32);
    const float_scene fs = prepare_float_scene(s);
    for (int64_t r = 0; r < f.height; ++r)
      for (int64_t c = 0; c < f.width; ++c)
        for (int k = 0; k < 3; ++k) {
          const float x = f.value(r, c, k);
          ASSERT_TRUE(std::isfinite(x)) << "row " << r << " col " << c;
          ASSERT_GE(x, fs.lo[k]) << "row " << r << " col " << c << " channel " << k;
          ASSERT_LE(x, fs.hi[k]) << "row " << r << " col " << c << " channel " << k;
        }
    const raycast_test::difference df = raycast_test::compare_to_reference_pixels(f, s);
    EXPECT_LE(df.max, bound(s.sky)) << df.where();
    const image b = render(s, pixel_format::rgb8);
    const raycast_test::difference d8 =
        raycast_test::compare(b, raycast_test::render_with_reference(s, pixel_format::rgb8));
    EXPECT_LE(d8.max, 1.0) << d8.where();
  }
};

scene make(const api::camera& p, const raycast::sky& s = {}) { return raycast_test::make_scene(p, s); }

// ------------------------------------------------------------------ 1. sizes

TEST_P(Numerics, DegenerateSizesAreFiniteAndMatchTheReference) {
  struct size_case {
    int64_t w;
    std::optional<int64_t> h;
    double aspect;
  };
  for (const size_case& c : {size_case{1, 225, 16.0 / 9.0}, size_case{400, 1, 16.0 / 9.0},
                             size_case{1, 1, 16.0 / 9.0}, size_case{400, std::nullopt, 100000.0},
                             size_case{3, std::nullopt, 1.0 / 100000.0}}) {
    api::camera p;
    p.width = c.w;
    p.height = c.h;
    p.aspect = c.aspect;
    const scene s = make(p);
    SCOPED_TRACE(std::to_string(s.cam.image_width) + "x" + std::to_string(s.cam.image_height));
    ASSERT_GE(s.cam.image_height, 1);
    expect_like_reference(s);
  }
}

// ------------------------------------------------------------------ 2. scale

TEST_P(Numerics, ScaleDoesNotChangeTheSky) {
  api::camera base;
  base.width = 64;
  base.height = 36;
  const image want = raycast_test::render_with_reference(make(base), pixel_format::rgb8);
  for (double k : {1e-30, 1e-20, 1e-10, 1e-3, 1e3, 1e10, 1e20, 1e30}) {
    SCOPED_TRACE("scale " + std::to_string(k));
    api::camera p = base;
    p.viewport_height = 2.0 * k;
    p.focal_length = 1.0 * k;
    const scene s = make(p);
    expect_like_reference(s);
    // The unit direction does not depend on scale: the image is the unscaled one.
    const raycast_test::difference d = raycast_test::compare(render(s, pixel_format::rgb8), want);
    EXPECT_LE(d.max, 1.0) << d.where();
  }
}

TEST_P(Numerics, MixedScalesMatchTheReferenceAndKeepTheirGradient) {
  struct mixed {
    double viewport, focal;
    bool gradient;  // does the true image vary from top to bottom?
  };
  for (const mixed& m : {mixed{1e30, 1e-30, true}, mixed{3e-38, 7e37, false},
                         mixed{1e-30, 1e30, false}, mixed{1e20, 1.0, true}}) {
    SCOPED_TRACE("viewport " + std::to_string(m.viewport) + " focal " + std::to_string(m.focal));
    api::camera p;
    p.width = 33;
    p.height = 17;
    p.viewport_height = m.viewport;
    p.focal_length = m.focal;
    const scene s = make(p);
    expect_like_reference(s);
    const image f = render(s, pixel_format::rgb_f32);
    if (m.gradient) {
      EXPECT_LT(f.value(0, 16, 0), f.value(16, 16, 0)) << "top row should be bluer than the bottom";
    } else {
      for (int64_t r = 0; r < f.height; ++r) EXPECT_EQ(f.value(r, 5, 0), f.value(0, 5, 0));
    }
  }
}

// ------------------------------------------------------------------ 3. far origin

TEST_P(Numerics, FarOriginGivesTheSameImageAsOriginZero) {
  api::camera p;
  p.width = 97;
  p.height = 41;
  const scene at_zero = make(p);
  for (const point3& o : {point3(1e8, -1e8, 1e12), point3(3.4e38, 3.4e38, 3.4e38),
                          point3(-3.4e38, -3.4e38, -3.4e38), point3(1e300, 0, -1e300)}) {
    SCOPED_TRACE("origin " + std::to_string(o.x) + "," + std::to_string(o.z));
    api::camera q = p;
    q.lookfrom = o;
    const scene far = make(q);
    for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32})
      EXPECT_EQ(render(far, f).bytes, render(at_zero, f).bytes);
  }
}

// ------------------------------------------------------------------ 4. exact directions

// With the focal length 1e-30 of a viewport 2 high, the middle column of a
// 3 x 3 image looks exactly up (top), horizontally (middle) and down (bottom)
// once the direction is in float: t must be exactly 1, 0.5 and 0.
TEST_P(Numerics, UpDownAndHorizontalGiveTheEndColoursExactly) {
  api::camera p;
  p.width = 3;
  p.height = 3;
  p.focal_length = 1e-30;
  for (const raycast::sky& sk : {raycast::sky{}, raycast::sky{{0.2, 0.9, 0.4}, {0.8, 0.1, 0.3}},
                                 raycast::sky{{4, -1, 0.5}, {0.25, 16, 2}}}) {
    const scene s = make(p, sk);
    const float_scene fs = prepare_float_scene(s);
    const image f = render(s, pixel_format::rgb_f32);
    const image b = render(s, pixel_format::rgb8);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(f.value(0, 1, k), fs.top[k]) << "straight up, channel " << k;
      EXPECT_EQ(f.value(2, 1, k), fs.bottom[k]) << "straight down, channel " << k;
      const float half = GetParam().which == backend::reference
                             ? float(0.5 * sk.bottom[k] + 0.5 * sk.top[k])  // in double
                             : fs.bottom[k] + 0.5f * fs.delta[k];            // scalar.h, t = 0.5
      EXPECT_EQ(f.value(1, 1, k), half) << "horizontal, channel " << k;
      EXPECT_EQ(b.byte(0, 1, k), to_byte(fs.top[k])) << "straight up, 8-bit, channel " << k;
      EXPECT_EQ(b.byte(2, 1, k), to_byte(fs.bottom[k])) << "straight down, 8-bit, channel " << k;
    }
  }
}

// The lesson's int(255.999 c) maps 1.0 to 255; colours above 1 or below 0
// clamp, so no byte wraps to 0 or 255 from the other end.
TEST_P(Numerics, EightBitNeverWraps) {
  api::camera p;
  p.width = 40;
  p.height = 30;
  const scene white = make(p, {{1, 1, 1}, {1, 1, 1}});
  for (unsigned char v : render(white, pixel_format::rgb8).bytes) ASSERT_EQ(v, 255);
  const scene over = make(p, {{1.5, 2, 1e6}, {1.0000001, 3, 1e9}});
  for (unsigned char v : render(over, pixel_format::rgb8).bytes) ASSERT_EQ(v, 255);
  const scene under = make(p, {{-0.5, -1e-9, -1e6}, {-2, -0.0, -1e9}});
  for (unsigned char v : render(under, pixel_format::rgb8).bytes) ASSERT_EQ(v, 0);
}

// ------------------------------------------------------------------ 5. FTZ / DAZ

#if defined(__x86_64__)
// Sets (or clears) the flush-to-zero and denormals-are-zero bits for the
// calling thread while alive; renders run with one thread, on this one.
class mxcsr_guard {
 public:
  explicit mxcsr_guard(bool on) : saved_(_mm_getcsr()) {
    const unsigned bits = 0x8040;  // FTZ (bit 15) | DAZ (bit 6)
    _mm_setcsr(on ? (saved_ | bits) : (saved_ & ~bits));
  }
  ~mxcsr_guard() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
};

TEST_P(Numerics, FlushToZeroAndDenormalsAreZeroChangeNothing) {
  std::vector<scene> scenes;
  api::camera p;
  p.width = 41;
  p.height = 23;
  scenes.push_back(make(p));
  p.focal_length = 1e-30;  // z^2 underflows: denormal or zero
  scenes.push_back(make(p));
  p.focal_length = 1e-19;  // z^2 is a denormal float
  scenes.push_back(make(p));
  p.focal_length = 7e37;
  p.viewport_height = 3e-38;  // the viewport vanishes next to the focal length
  scenes.push_back(make(p));
  // Denormal and tiny sky colours (the lerp would otherwise produce denormals).
  scenes.push_back(make(api::camera{}, {{1e-39, 0.5, 1e-40}, {1e-38, 2e-39, 0.75}}));
  scenes.push_back(make(api::camera{}, {{3e-30, 1e-25, 0}, {-2e-30, 5e-26, 1e-21}}));
  for (const scene& s : scenes) {
    for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
      image off, on;
      {
        mxcsr_guard g(false);
        off = render(s, f);
      }
      {
        mxcsr_guard g(true);
        on = render(s, f);
      }
      EXPECT_EQ(off.bytes, on.bytes) << "focal " << s.cam.focal_length;
    }
  }
}
#endif

// ------------------------------------------------------------------ 7. size limits

// W * H * 3 far above 2^32: a band of rows near the bottom of a huge virtual
// image lands where 64-bit row and column arithmetic says it should.
TEST_P(Numerics, HugeVirtualImageBandsUseSixtyFourBitIndexing) {
  api::camera p;
  p.width = 70001;
  p.height = 40000;  // 70001 * 40000 * 3 = 8.4e9 bytes > 2^32
  const scene s = make(p);
  for (int64_t r0 : {int64_t{0}, p.height.value() / 2 - 1, p.height.value() - 2}) {
    image band(p.width, 2, pixel_format::rgb8);
    image_band b = band.band();
    b.row_begin = r0;
    b.row_end = r0 + 2;
    renderer(s, {GetParam().which, GetParam().prec, 1}).render(b);
    for (int64_t r = 0; r < 2; ++r) {
      const int64_t j = s.cam.image_height - 1 - (r0 + r);
      for (int64_t i : {int64_t{0}, int64_t{1}, p.width / 2, p.width - 1}) {
        const color c = reference_pixel(s, i, j);
        for (int k = 0; k < 3; ++k)
          EXPECT_LE(std::abs(band.byte(r, i, k) - int(to_byte(c[k]))), 1)
              << "row " << r0 + r << " column " << i;
      }
    }
  }
}

// ------------------------------------------------------------------ 8. HDR

TEST_P(Numerics, HdrColoursReachFloatOutputUnclamped) {
  api::camera p;
  p.width = 50;
  p.height = 30;
  const raycast::sky hdr{{4.0, 2.0, 0.5}, {-1.0, 0.25, 16.0}};
  const scene s = make(p, hdr);
  expect_like_reference(s);
  const image f = render(s, pixel_format::rgb_f32);
  EXPECT_GT(f.value(29, 25, 0), 1.0f) << "red near the bottom is above 1";
  EXPECT_GT(f.value(0, 25, 2), 1.0f) << "blue near the top is above 1";
  const image b = render(s, pixel_format::rgb8);
  EXPECT_EQ(b.byte(29, 25, 0), 255);
  EXPECT_EQ(b.byte(0, 25, 2), 255);
}

// ------------------------------------------------------------------ 9. error bounds

// The documented bounds (scalar.h, src/kernels/README.md) hold on the cases that
// push the error hardest: the widest sky spans and many directions.
TEST_P(Numerics, DocumentedErrorBoundsHoldAtTheirEdge) {
  api::camera p;
  p.width = 1031;
  p.height = 517;
  p.viewport_height = 9.0;
  p.focal_length = 0.3;
  for (const raycast::sky& sk : {raycast::sky{}, raycast::sky{{0, 0, 0}, {1, 1, 1}},
                                 raycast::sky{{1e4, -1e4, 0}, {-1e4, 1e4, 1}}}) {
    expect_like_reference(make(p, sk));
  }
  // A focal length tiny next to the viewport: every direction lies almost in
  // the viewport plane, and the pixels next to the centre are the hardest.
  api::camera q;
  q.width = 400;
  q.height = 225;
  q.viewport_height = 1e30;
  q.focal_length = 1e-30;
  for (const raycast::sky& sk : {raycast::sky{}, raycast::sky{{4.0, 2.0, 0.5}, {-1.0, 0.25, 16.0}}})
    expect_like_reference(make(q, sk));
}

// Every named stiff case of the benchmark's stiff section.
TEST_P(Numerics, EveryStiffCaseMatchesTheReference) {
  for (const stiff_case& c : stiff_cases()) {
    SCOPED_TRACE(c.name);
    expect_like_reference(make(c.cam, c.sky));
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Numerics, ::testing::ValuesIn(raycast_test::all_modes()),
                         raycast_test::mode_name);

// All backends agree with each other on the degenerate sizes too: in exact
// mode, the same bits as the scalar float renderer.
class DegenerateSizes : public raycast_test::backend_test<backend> {};

TEST_P(DegenerateSizes, EveryBackendGivesTheScalarRenderersBits) {
  const backend b = GetParam();
  for (auto [w, h] : {std::pair<int64_t, int64_t>{1, 1}, {1, 225}, {400, 1}, {3, 300000}}) {
    api::camera p;
    p.width = w;
    p.height = h;
    const scene s = make(p);
    for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32})
      EXPECT_EQ(raycast_test::render_with(renderer(s, {b, precision::exact, 1}), f).bytes,
                raycast_test::render_with_scalar(s, precision::exact, f).bytes)
          << to_string(b) << " " << w << "x" << h;
  }
}

INSTANTIATE_TEST_SUITE_P(SimdBackends, DegenerateSizes, ::testing::ValuesIn(simd_backends),
                         raycast_test::backend_name);

TEST(SizeLimits, WidthsAboveTwoToTheTwentyFourAreRefusedWithTheLimit) {
  api::camera p;
  p.width = max_dimension;
  p.height = 1;
  EXPECT_FALSE(validate(p).has_value());
  p.width = max_dimension + 1;
  const auto e = validate(p);
  ASSERT_TRUE(e.has_value());
  EXPECT_NE(e->message.find(std::to_string(max_dimension)), std::string::npos) << e->message;
}

TEST(SizeLimits, SkyColoursBeyondTheLimitAreRefused) {
  EXPECT_FALSE(validate(api::sky{}).has_value());
  EXPECT_TRUE(validate(api::sky{{1e31, 0, 0}, {1, 1, 1}}).has_value());
  EXPECT_TRUE(validate(api::sky{{1, 1, 1}, {0, NAN, 0}}).has_value());
}

}  // namespace
