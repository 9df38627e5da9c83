// Antialiasing (the book's ch. 7):
//  - the samplers: offsets in [0, 1), the same for the same (seed, pixel,
//    sample) and not for another seed; stratified puts one sample in each
//    stratum, sobol one in every elementary interval of a power-of-two net;
//  - exact mode: every SIMD backend's many-sample render bit-identical to the
//    scalar float renderer's (scene/sampler.h, kernels/scalar.h), in both
//    precisions, 8-bit and float, odd sizes, every sampler; a dust of spheres
//    smaller than a pixel checks that culling widened by the pixel's spread
//    loses none;
//  - threads, bands and regions (image_band's column window) give the same
//    bytes as the whole image, one sample or many, sky kernel or sphere kernel;
//  - the float average against the double reference's average over the same
//    samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "backend_test.h"
#include "render_support.h"
#include "scene/builtin.h"
#include "sampling/sampler.h"

namespace {

using namespace raycast;
using raycast_test::image;

constexpr sampler_kind every_sampler[] = {sampler_kind::random, sampler_kind::stratified, sampler_kind::sobol};

// ------------------------------------------------------------ the samplers

TEST(Samplers, OffsetsLieInTheUnitSquareAndRepeatForTheSameKey) {
  for (sampler_kind k : every_sampler) {
    SCOPED_TRACE(std::string(to_string(k)));
    const sampling::sample_table t(k, 37, 5), again(k, 37, 5), other(k, 37, 6);
    int differ = 0;
    for (uint32_t i = 0; i < 40; i += 3)
      for (uint32_t j = 0; j < 40; j += 7)
        for (uint32_t s = 0; s < 37; ++s) {
          float x, y, x2, y2, x3, y3;
          sampling::sample_offsets(t.plan(), i, j, s, x, y);
          sampling::sample_offsets(again.plan(), i, j, s, x2, y2);
          sampling::sample_offsets(other.plan(), i, j, s, x3, y3);
          ASSERT_TRUE(x >= 0.0f && x < 1.0f && y >= 0.0f && y < 1.0f) << x << " " << y;
          ASSERT_EQ(x, x2);
          ASSERT_EQ(y, y2);
          differ += x != x3 || y != y3;
        }
    EXPECT_GT(differ, 14 * 6 * 37 * 9 / 10) << "another seed must give other samples";
  }
}

// Neighbouring pixels draw unrelated samples (no shared stream, no pattern
// repeated across the image): their first samples' offsets are not equal.
TEST(Samplers, NeighbouringPixelsDrawDifferentSamples) {
  for (sampler_kind k : every_sampler) {
    const sampling::sample_table t(k, 4, 0);
    std::set<std::pair<float, float>> seen;
    for (uint32_t i = 0; i < 32; ++i)
      for (uint32_t j = 0; j < 32; ++j) {
        float x, y;
        sampling::sample_offsets(t.plan(), i, j, 0, x, y);
        seen.insert({x, y});
      }
    EXPECT_GT(seen.size(), 1000u) << to_string(k);
  }
}

// Stratified: an nx x ny grid, one sample per stratum (12 = 3 x 4; 7, a
// prime, is 1 x 7).
TEST(Samplers, StratifiedPutsOneSampleInEachStratum) {
  for (uint32_t n : {4u, 7u, 12u, 16u, 100u}) {
    const sampling::sample_table t(sampler_kind::stratified, n, 3);
    const uint32_t nx = t.plan().nx, ny = t.plan().ny;
    ASSERT_EQ(nx * ny, n);
    ASSERT_LE(nx, ny);
    for (uint32_t pixel = 0; pixel < 20; ++pixel) {
      std::set<std::pair<int, int>> cells;
      for (uint32_t s = 0; s < n; ++s) {
        float x, y;
        sampling::sample_offsets(t.plan(), pixel, 2 * pixel, s, x, y);
        cells.insert({int(x * float(nx)), int(y * float(ny))});
      }
      EXPECT_EQ(cells.size(), n) << n << " samples";
    }
  }
}

// Sobol with a per-pixel digital shift: the first 2^m points are a (0, m, 2)-net -- one point
// in each of the 2^m rectangles 2^-a x 2^-(m-a), for every a -- in every pixel.
TEST(Samplers, SobolIsANetInEveryPixel) {
  for (int m : {2, 4, 6, 8}) {
    const uint32_t n = 1u << m;
    const sampling::sample_table t(sampler_kind::sobol, n, 11);
    for (uint32_t pixel = 0; pixel < 10; ++pixel) {
      std::vector<float> xs(n), ys(n);
      for (uint32_t s = 0; s < n; ++s) sampling::sample_offsets(t.plan(), 7 * pixel, pixel, s, xs[s], ys[s]);
      for (int a = 0; a <= m; ++a) {
        std::set<std::pair<int, int>> cells;
        for (uint32_t s = 0; s < n; ++s)
          cells.insert({int(xs[s] * float(1 << a)), int(ys[s] * float(1 << (m - a)))});
        EXPECT_EQ(cells.size(), n) << n << " points, intervals 2^-" << a << " x 2^-" << m - a;
      }
    }
  }
}

// The random sampler's offsets are uniform: the mean of many is near 1/2 and
// each tenth of [0, 1) gets about a tenth.
TEST(Samplers, RandomOffsetsAreUniform) {
  const sampling::sample_table t(sampler_kind::random, 64, 1);
  double sum = 0;
  int bins[10] = {};
  int n = 0;
  for (uint32_t i = 0; i < 50; ++i)
    for (uint32_t s = 0; s < 64; ++s, n += 2) {
      float x, y;
      sampling::sample_offsets(t.plan(), i, 9, s, x, y);
      sum += x + y;
      ++bins[int(x * 10)];
      ++bins[int(y * 10)];
    }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
  for (int b : bins) EXPECT_NEAR(b, n / 10, n / 10 / 5);
}

// ------------------------------------------------------------ renders

struct aa_case {
  std::string name;
  std::vector<sphere> spheres;
  api::camera cam;
};

// A dust of spheres far smaller than a pixel: most of them fall between the
// one-sample rays, so only culling that covers the pixel's whole square of
// samples keeps every sphere a sample can hit.
std::vector<sphere> dust() {
  std::vector<sphere> v;
  uint32_t h = 12345;
  for (int k = 0; k < 300; ++k) {
    const auto next = [&] { return double((h = sampling::mix(h)) >> 8) * 0x1p-24; };
    const double x = next() * 3.2 - 1.6, y = next() * 1.8 - 0.9;
    v.push_back({{x, y, -1.0}, 0.0005 + 0.002 * next(), k % 3 ? shading::normal : shading::flat,
                 color(next(), next(), next())});
  }
  return v;
}

const std::vector<aa_case>& aa_cases() {
  static const std::vector<aa_case> all = [] {
    std::vector<aa_case> v;
    v.push_back({"world", *builtin_spheres("world"), {}});
    v.push_back({"sky", {}, {}});
    api::camera tilted;
    tilted.lookfrom = {-2, 2, 1};
    tilted.lookat = vec3{0, 0, -1};
    tilted.vfov = 40;
    v.push_back({"tilted_world", *builtin_spheres("world"), tilted});
    v.push_back({"camera_inside", {{{0.1, -0.2, 0.0}, 2.0, shading::normal}, {{0, 0, -1}, 0.5, shading::normal}}, {}});
    v.push_back({"dust", dust(), {}});
    // Lit, flat and normal spheres together (the general path), one lit
    // around the camera.
    v.push_back({"lit_mixed",
                 {{{0.0, 0.0, -1.0}, 0.5, shading::lit, {1.0, 0.55, 0.1}},
                  {{0.0, -100.5, -1.0}, 100.0, shading::normal},
                  {{0.7, 0.1, -1.3}, 0.3, shading::flat, {0.2, 0.9, 0.3}},
                  {{-0.6, 0.0, -1.1}, 0.25, shading::lit, {0.3, 0.3, 1.5}},
                  {{0.0, 0.0, 0.0}, 20.0, shading::lit, {0.5, 0.5, 0.5}}},
                 {}});
    return v;
  }();
  return all;
}

scene make(const aa_case& c, int64_t w, int64_t h) {
  api::camera cp = c.cam;
  cp.width = w;
  cp.height = h;
  return raycast_test::make_scene(cp, {}, c.spheres);
}

render_options sampled(backend b, precision p, uint32_t n, sampler_kind k, int threads = 1, uint64_t seed = 0) {
  render_options o;
  o.which = b;
  o.prec = p;
  o.threads = threads;
  o.samples = n;
  o.sampler = k;
  o.seed = seed;
  return o;
}

image scalar_samples(const scene& s, pixel_format f, uint32_t n, sampler_kind k, uint64_t seed = 0) {
  render_options o = sampled(backend::scalar, precision::exact, n, k, 1, seed);
  o.shortcuts = shortcut::none;
  return raycast_test::render_with(renderer(s, o), f);
}

struct backend_param {
  backend which;
  precision prec;
};

std::vector<backend_param> simd_params() {
  std::vector<backend_param> v;
  for (backend b : simd_backends)
    for (precision p : {precision::exact, precision::fast}) v.push_back({b, p});
  return v;
}

class SampledEquivalence : public raycast_test::backend_test<backend_param> {};

// Many samples per pixel: the SIMD bytes and floats are the scalar renderer's
// (both precisions: the sampled path is exact), for every sampler, at sizes
// that end rows inside a batch.
TEST_P(SampledEquivalence, BitIdenticalToScalar) {
  const std::pair<int64_t, int64_t> sizes[] = {{1, 1}, {17, 9}, {64, 36}, {101, 57}};
  for (const aa_case& c : aa_cases())
    for (const auto& [w, h] : sizes) {
      const scene s = make(c, w, h);
      for (sampler_kind k : every_sampler)
        for (uint32_t n : {2u, 5u, 16u}) {
          SCOPED_TRACE(c.name + " " + std::to_string(w) + "x" + std::to_string(h) + " " +
                       std::string(to_string(k)) + " " + std::to_string(n));
          const renderer r(s, sampled(GetParam().which, GetParam().prec, n, k));
          for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
            const image want = scalar_samples(s, f, n, k);
            const image got = raycast_test::render_with(r, f);
            ASSERT_EQ(got.bytes, want.bytes) << raycast_test::compare(got, want).where();
          }
        }
    }
}

// The sub-pixel dust at a size where most spheres fall between pixel centres,
// 64 samples: every sphere a sample hits is in its batch's list.
TEST_P(SampledEquivalence, CullingKeepsSpheresBetweenPixelCentres) {
  const scene s = make(aa_cases()[4], 160, 90);
  const image want = scalar_samples(s, pixel_format::rgb_f32, 64, sampler_kind::sobol);
  const image got =
      raycast_test::render_with(renderer(s, sampled(GetParam().which, GetParam().prec, 64, sampler_kind::sobol)),
                                pixel_format::rgb_f32);
  ASSERT_EQ(got.bytes, want.bytes) << raycast_test::compare(got, want).where();
  // ...and the dust shows: a one-sample render misses most of it.
  const image one = raycast_test::render_with(renderer(s, sampled(GetParam().which, GetParam().prec, 1, sampler_kind::sobol)),
                                              pixel_format::rgb_f32);
  EXPECT_GT(raycast_test::compare(one, got).max, 0.05);
}

// The same bytes on 1 and 2 threads, and for a band in the middle.
TEST_P(SampledEquivalence, ThreadsAndBandsGiveTheSameBytes) {
  const scene s = make(aa_cases()[0], 320, 180);
  const render_options o = sampled(GetParam().which, GetParam().prec, 9, sampler_kind::stratified, 1, 42);
  const image want = raycast_test::render_with(renderer(s, o), pixel_format::rgb8);
  render_options two = o;
  two.threads = 2;
  const image got = raycast_test::render_with(renderer(s, two), pixel_format::rgb8);
  EXPECT_EQ(got.bytes, want.bytes) << raycast_test::compare(got, want).where();
  image band(320, 180, pixel_format::rgb8);
  image_band b = band.band();
  b.row_begin = 50;
  b.row_end = 121;
  b.data = band.bytes.data() + 50 * band.stride();
  renderer(s, o).render(b);
  EXPECT_TRUE(std::equal(want.bytes.begin() + 50 * long(want.stride()), want.bytes.begin() + 121 * long(want.stride()),
                         band.bytes.begin() + 50 * long(band.stride())));
}

// A region -- any window of columns and rows, its edges anywhere in a batch
// -- is the same bytes as those pixels of the whole image: one sample (the
// sky kernel in both precisions, with its mirror shortcuts off; the sphere
// kernel) and many.
TEST_P(SampledEquivalence, RegionsAreThePixelsOfTheWholeImage) {
  struct window {
    int64_t x0, y0, x1, y1;
  };
  const window windows[] = {{0, 0, 203, 117}, {202, 116, 203, 117}, {5, 3, 38, 9},   {16, 0, 32, 1},
                            {190, 0, 203, 117}, {0, 100, 203, 117},         {37, 41, 150, 42}};
  for (const aa_case& c : {aa_cases()[0], aa_cases()[1], aa_cases()[2]})
    for (uint32_t n : {1u, 6u})
      for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
        SCOPED_TRACE(c.name + " samples " + std::to_string(n));
        const scene s = make(c, 203, 117);
        const renderer r(s, sampled(GetParam().which, GetParam().prec, n, sampler_kind::random, 1, 9));
        const image whole = raycast_test::render_with(r, f);
        for (const window& w : windows) {
          SCOPED_TRACE(std::to_string(w.x0) + "," + std::to_string(w.y0) + "," + std::to_string(w.x1) + "," +
                       std::to_string(w.y1));
          image part(w.x1 - w.x0, w.y1 - w.y0, f);
          image_band b = part.band();
          b.row_begin = w.y0;
          b.row_end = w.y1;
          b.col_begin = w.x0;
          b.col_end = w.x1;
          r.render(b);
          const size_t bpp = bytes_per_pixel(f);
          for (int64_t y = w.y0; y < w.y1; ++y)
            ASSERT_TRUE(std::equal(part.bytes.begin() + long((y - w.y0) * (w.x1 - w.x0) * bpp),
                                   part.bytes.begin() + long((y - w.y0 + 1) * (w.x1 - w.x0) * bpp),
                                   whole.bytes.begin() + long((y * 203 + w.x0) * bpp)))
                << "row " << y;
        }
      }
}

std::string param_name(const ::testing::TestParamInfo<backend_param>& i) {
  return std::string(to_string(i.param.which)) + "_" + std::string(to_string(i.param.prec));
}

INSTANTIATE_TEST_SUITE_P(Simd, SampledEquivalence, ::testing::ValuesIn(simd_params()), param_name);

// The scalar and reference backends take regions and samples too.
TEST(SampledRender, ScalarAndReferenceBackendsTakeRegions) {
  const scene s = make(aa_cases()[0], 90, 50);
  for (backend b : {backend::scalar, backend::reference}) {
    const renderer r(s, sampled(b, precision::exact, 4, sampler_kind::sobol));
    const image whole = raycast_test::render_with(r, pixel_format::rgb8);
    image part(30, 20, pixel_format::rgb8);
    image_band band = part.band();
    band.row_begin = 10;
    band.row_end = 30;
    band.col_begin = 45;
    band.col_end = 75;
    r.render(band);
    for (int64_t y = 10; y < 30; ++y)
      for (int64_t x = 45; x < 75; ++x)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(part.byte(y - 10, x - 45, k), whole.byte(y, x, k)) << to_string(b);
  }
}

// The float renderer's average against the double reference's over the same
// sample offsets: equal but for rounding, except where a sample's ray lands
// on the other side of a silhouette in float (one sample of n changes the
// pixel by at most 1/n of the colours' difference).
TEST(SampledRender, FloatAverageMatchesTheDoubleReference) {
  for (const aa_case& c : {aa_cases()[0], aa_cases()[2]}) {
    const scene s = make(c, 200, 112);
    const uint32_t n = 16;
    const sampling::sample_table t(sampler_kind::sobol, n, 0);
    image ref(200, 112, pixel_format::rgb_f32);
    render_reference(s, ref.band(), &t.plan());
    const image got = scalar_samples(s, pixel_format::rgb_f32, n, sampler_kind::sobol);
    double worst = 0, sum = 0;
    int64_t over = 0;
    for (int64_t y = 0; y < 112; ++y)
      for (int64_t x = 0; x < 200; ++x)
        for (int k = 0; k < 3; ++k) {
          const double d = std::abs(double(got.value(y, x, k)) - double(ref.value(y, x, k)));
          worst = std::max(worst, d);
          sum += d;
          over += d > 1e-5;
        }
    EXPECT_LE(worst, 1.0 / n) << c.name;
    EXPECT_LE(sum / (200 * 112 * 3), 3e-6) << c.name;
    EXPECT_LE(over, 200 * 112 * 3 / 1000) << c.name << ": pixels off by more than rounding";
  }
}

// More samples converge: the 256-sample image of `world` is closer to a
// 4096-sample stratified reference than the 4-sample one, by about the
// samplers' rates (random 1/sqrt(n); sobol and stratified faster).
TEST(SampledRender, ErrorFallsWithMoreSamples) {
  const scene s = make(aa_cases()[0], 80, 45);
  const sampling::sample_table t(sampler_kind::stratified, 4096, 99);
  image ref(80, 45, pixel_format::rgb_f32);
  render_reference(s, ref.band(), &t.plan());
  const auto rmse = [&](const image& a) {
    double sum = 0;
    for (int64_t y = 0; y < 45; ++y)
      for (int64_t x = 0; x < 80; ++x)
        for (int k = 0; k < 3; ++k) sum += std::pow(double(a.value(y, x, k)) - double(ref.value(y, x, k)), 2);
    return std::sqrt(sum / (80 * 45 * 3));
  };
  for (sampler_kind k : every_sampler) {
    const double e4 = rmse(scalar_samples(s, pixel_format::rgb_f32, 4, k));
    const double e256 = rmse(scalar_samples(s, pixel_format::rgb_f32, 256, k));
    EXPECT_LT(e256, e4 / 5) << to_string(k) << ": " << e4 << " -> " << e256;
  }
}

}  // namespace
