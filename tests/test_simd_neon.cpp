// The NEON vector layer op by op (simd/neon.h), against the scalar meaning the
// kernel relies on: scalar.cpp's a > b ? a : b for max and min (NaN and signed
// zeros included, where NEON's own fmax differs), lane order for reverse, the
// byte layout of pack_rgb8 + store, store_rgbf's interleaving, truncation in
// to_int, and rsqrt_est's accuracy. Built on AArch64 only (in CI, under qemu);
// the whole-image equivalence tests cover the rest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "simd/neon.h"

namespace {

using namespace raycast::simd::neon;

constexpr int N = vfloat::size;

vfloat from(const float (&x)[N]) { return vfloat::load(x); }
void to(vfloat v, float (&x)[N]) {
  vst1q_f32(x, v.lo);
  vst1q_f32(x + 4, v.hi);
}
void to(vint v, int32_t (&x)[N]) {
  vst1q_s32(x, v.lo);
  vst1q_s32(x + 4, v.hi);
}
vint ints(const int32_t (&x)[N]) { return {vld1q_s32(x), vld1q_s32(x + 4)}; }
uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

TEST(SimdNeon, MaxAndMinHaveTheScalarRenderersMeaningForNanAndSignedZeros) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float a[N] = {1.0f, -0.0f, 0.0f, nan, 2.0f, nan, -3.0f, 5.0f};
  const float b[N] = {2.0f, 0.0f, -0.0f, 1.0f, nan, nan, -4.0f, 5.0f};
  float mx[N], mn[N];
  to(max(from(a), from(b)), mx);
  to(min(from(a), from(b)), mn);
  for (int k = 0; k < N; ++k) {
    const float want_max = a[k] > b[k] ? a[k] : b[k], want_min = a[k] < b[k] ? a[k] : b[k];
    EXPECT_EQ(bits(mx[k]), bits(want_max)) << "max lane " << k;
    EXPECT_EQ(bits(mn[k]), bits(want_min)) << "min lane " << k;
  }
}

TEST(SimdNeon, ArithmeticRoundsOnceLikeScalarFloat) {
  const float a[N] = {1.1f, 3.0f, 1e-38f, 7.0f, 0.1f, 1e30f, 2.0f, 1.0f / 3.0f};
  const float b[N] = {2.3f, 7.0f, 3.0f, 1e-7f, 0.2f, 1e10f, 0.5f, 3.0f};
  const float c[N] = {-2.53f, 0.5f, 1.0f, -7.0f, 0.3f, 1e35f, -1.0f, -1.0f};
  float got[N];
  // a * b + c in two roundings: never fused (the kernel's exact mode).
  to(from(a) * from(b) + from(c), got);
  for (int k = 0; k < N; ++k) {
    volatile float p = a[k] * b[k];
    EXPECT_EQ(bits(got[k]), bits(p + c[k])) << "lane " << k;
  }
  to(from(a) / sqrt(from(b)), got);
  for (int k = 0; k < N; ++k) EXPECT_EQ(bits(got[k]), bits(a[k] / std::sqrt(b[k]))) << "lane " << k;
}

TEST(SimdNeon, SelectAndEqual) {
  const float t[N] = {1, 0.5f, 1, 0, 1, 1, -1, 1};
  const float x[N] = {10, 11, 12, 13, 14, 15, 16, 17}, y[N] = {20, 21, 22, 23, 24, 25, 26, 27};
  float got[N];
  to(select(from(t) == vfloat(1.0f), from(x), from(y)), got);
  for (int k = 0; k < N; ++k) EXPECT_EQ(got[k], t[k] == 1.0f ? x[k] : y[k]) << "lane " << k;
}

TEST(SimdNeon, ReverseTurnsTheLaneOrderAround) {
  const float x[N] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int32_t i[N] = {10, 11, 12, 13, 14, 15, 16, 17};
  float got[N];
  int32_t goti[N];
  to(reverse(from(x)), got);
  to(reverse(ints(i)), goti);
  for (int k = 0; k < N; ++k) {
    EXPECT_EQ(got[k], x[N - 1 - k]);
    EXPECT_EQ(goti[k], i[N - 1 - k]);
  }
}

TEST(SimdNeon, ToIntTruncates) {
  const float x[N] = {0.0f, 0.999f, 1.0f, 254.999f, 255.999f, 127.5f, 3.99999f, 200.0f};
  int32_t got[N];
  to(to_int(from(x)), got);
  for (int k = 0; k < N; ++k) EXPECT_EQ(got[k], int32_t(x[k])) << "lane " << k;
}

TEST(SimdNeon, PackAndStoreWriteExactlyTwentyFourInterleavedBytes) {
  const int32_t r[N] = {0, 1, 2, 3, 4, 5, 6, 255}, g[N] = {10, 11, 12, 13, 14, 15, 16, 17},
                b[N] = {20, 21, 22, 23, 24, 25, 26, 128};
  for (bool reversed : {false, true}) {
    std::vector<unsigned char> buf(3 * N + 2, 0xA5);
    store(buf.data() + 1, reversed ? pack_rgb8<true>(ints(r), ints(g), ints(b))
                                   : pack_rgb8<false>(ints(r), ints(g), ints(b)));
    EXPECT_EQ(buf.front(), 0xA5);
    EXPECT_EQ(buf.back(), 0xA5);
    for (int p = 0; p < N; ++p) {
      const int src = reversed ? N - 1 - p : p;
      EXPECT_EQ(buf[1 + 3 * p + 0], r[src]) << "pixel " << p << (reversed ? " reversed" : "");
      EXPECT_EQ(buf[1 + 3 * p + 1], g[src]) << "pixel " << p << (reversed ? " reversed" : "");
      EXPECT_EQ(buf[1 + 3 * p + 2], b[src]) << "pixel " << p << (reversed ? " reversed" : "");
    }
  }
}

TEST(SimdNeon, StoreRgbfInterleavesTwentyFourFloats) {
  const float r[N] = {0, 1, 2, 3, 4, 5, 6, 7}, g[N] = {10, 11, 12, 13, 14, 15, 16, 17},
              b[N] = {20, 21, 22, 23, 24, 25, 26, 27};
  std::vector<float> out(3 * N + 1, -1.0f);
  store_rgbf(out.data(), from(r), from(g), from(b));
  for (int p = 0; p < N; ++p) {
    EXPECT_EQ(out[3 * p + 0], r[p]);
    EXPECT_EQ(out[3 * p + 1], g[p]);
    EXPECT_EQ(out[3 * p + 2], b[p]);
  }
  EXPECT_EQ(out.back(), -1.0f);
}

// FRSQRTE + one FRSQRTS step: finer than x86's rsqrtps (1.5 * 2^-12), which is
// what the kernel's single biased Newton step was designed for.
TEST(SimdNeon, RsqrtEstimateIsAtLeastAsFineAsX86s) {
  double worst = 0;
  for (uint32_t u = 0x3f800000u; u < 0x40800000u; u += 97) {  // [1, 4): the estimate's period
    float x[N];
    for (int k = 0; k < N; ++k) {
      const uint32_t v = u + uint32_t(k);
      std::memcpy(&x[k], &v, 4);
    }
    float got[N];
    to(rsqrt_est(from(x)), got);
    for (int k = 0; k < N; ++k)
      worst = std::fmax(worst, std::fabs(double(got[k]) * std::sqrt(double(x[k])) - 1.0));
  }
  EXPECT_LT(worst, 1.5 * 0x1p-12);
  EXPECT_LT(worst, 0x1p-15);  // measured 2^-15.9
}

}  // namespace
