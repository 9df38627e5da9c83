// Each lane-moving operation of the vector layer (src/simd/) on its own, on
// every instruction set this build has, so that a wrong reverse or pack fails
// here by name instead of as a pixel difference somewhere in an image. An
// instruction set this CPU (or RAYCAST_MAX_ISA) cannot run is skipped with the
// reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "render/backend.h"
#include "simd_ops/ops.h"

namespace {

using namespace raycast;
using raycast_test::simd_ops;

struct isa {
  backend which;
  const simd_ops* ops;
};

class SimdOps : public ::testing::TestWithParam<isa> {
 protected:
  void SetUp() override {
    if (auto why = backend_unavailable(GetParam().which))
      GTEST_SKIP() << to_string(GetParam().which) << ": " << *why;
    ops = GetParam().ops;
    n = ops->lanes;
  }
  // i * step + start in lane i.
  std::vector<float> iota(float start = 0.0f, float step = 1.0f) const {
    std::vector<float> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) v[size_t(i)] = start + step * float(i);
    return v;
  }
  const simd_ops* ops = nullptr;
  int n = 0;
};

TEST_P(SimdOps, LoadAndStoreKeepLaneOrder) {
  const std::vector<float> in = iota();
  std::vector<float> out(static_cast<size_t>(n));
  ops->load_store(in.data(), out.data());
  EXPECT_EQ(out, in);
}

TEST_P(SimdOps, ReverseMirrorsTheLanes) {
  const std::vector<float> in = iota();
  std::vector<float> out(static_cast<size_t>(n));
  ops->reverse(in.data(), out.data());
  for (int i = 0; i < n; ++i) EXPECT_EQ(out[size_t(i)], float(n - 1 - i)) << "lane " << i;
}

TEST_P(SimdOps, ScalarOperandsBroadcastAndNegationFlipsTheSign) {
  const std::vector<float> in = iota();  // lane 0 is +0: its negation is -0
  std::vector<float> half(static_cast<size_t>(n)), neg(static_cast<size_t>(n));
  ops->half_plus_and_negate(in.data(), half.data(), neg.data());
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(half[size_t(i)], (float(i) + 1.0f) * 0.5f) << "lane " << i;
    EXPECT_EQ(neg[size_t(i)], -float(i)) << "lane " << i;
    EXPECT_TRUE(std::signbit(neg[size_t(i)])) << "lane " << i;
  }
}

TEST_P(SimdOps, SelectTakesTheFirstWhereTheMaskHolds) {
  std::vector<float> key(static_cast<size_t>(n)), out(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) key[size_t(i)] = float(i % 3);
  const std::vector<float> a = iota(10.0f);
  ops->select_zero(key.data(), a.data(), -1.0f, out.data());
  for (int i = 0; i < n; ++i)
    EXPECT_EQ(out[size_t(i)], i % 3 == 0 ? 10.0f + float(i) : -1.0f) << "lane " << i;
}

// Ordered comparisons (NaN compares false), masks combined and tested, and
// the all-false mask vmask{} (what the sphere kernel's closest hit starts from).
TEST_P(SimdOps, ComparisonsAndMasks) {
  const size_t N = size_t(n);
  std::vector<float> a(N), b(N), ge(N), le(N), both(N), either(N), not_ge(N), empty(N);
  for (int i = 0; i < n; ++i) {
    a[size_t(i)] = i % 4 == 3 ? NAN : float(i % 3);
    b[size_t(i)] = 1.0f;
  }
  bool any_ge = false, none_ge = true, all_ge = true;
  ops->compare(a.data(), b.data(), ge.data(), le.data(), both.data(), either.data(), &any_ge, &none_ge,
               &all_ge, not_ge.data(), empty.data());
  for (size_t i = 0; i < N; ++i) {
    const float x = a[i];
    EXPECT_EQ(ge[i], x >= 1.0f ? 1.0f : 0.0f) << "lane " << i;
    EXPECT_EQ(le[i], x <= 1.0f ? 1.0f : 0.0f) << "lane " << i;
    EXPECT_EQ(both[i], x == 1.0f ? 1.0f : 0.0f) << "lane " << i;
    EXPECT_EQ(either[i], std::isnan(x) ? 0.0f : 1.0f) << "lane " << i;
    EXPECT_EQ(not_ge[i], x >= 1.0f ? 0.0f : 1.0f) << "lane " << i;
    EXPECT_EQ(empty[i], 0.0f) << "lane " << i;
  }
  EXPECT_TRUE(any_ge);
  EXPECT_FALSE(none_ge);
  EXPECT_FALSE(all_ge);
  std::fill(a.begin(), a.end(), 2.0f);
  ops->compare(a.data(), b.data(), ge.data(), le.data(), both.data(), either.data(), &any_ge, &none_ge,
               &all_ge, not_ge.data(), empty.data());
  EXPECT_TRUE(all_ge);
  a[0] = NAN;  // only the first lane: the low half on SSE2
  ops->compare(a.data(), b.data(), ge.data(), le.data(), both.data(), either.data(), &any_ge, &none_ge,
               &all_ge, not_ge.data(), empty.data());
  EXPECT_FALSE(all_ge);
  EXPECT_EQ(not_ge[0], 1.0f);
  std::fill(a.begin(), a.end(), 0.5f);
  a[N - 1] = 1.0f;  // only the last lane: the high half on SSE2
  ops->compare(a.data(), b.data(), ge.data(), le.data(), both.data(), either.data(), &any_ge, &none_ge,
               &all_ge, not_ge.data(), empty.data());
  EXPECT_TRUE(any_ge);
  a[N - 1] = NAN;
  ops->compare(a.data(), b.data(), ge.data(), le.data(), both.data(), either.data(), &any_ge, &none_ge,
               &all_ge, not_ge.data(), empty.data());
  EXPECT_FALSE(any_ge);
  EXPECT_TRUE(none_ge);
}

TEST_P(SimdOps, CopysignIsStdCopysign) {
  const size_t N = size_t(n);
  const float mags[] = {0.0f, -0.0f, 1.5f, -2.25f, INFINITY, 3e-42f};
  const float signs[] = {1.0f, -1.0f, 0.0f, -0.0f, -INFINITY, NAN};
  std::vector<float> m(N), s(N), out(N);
  for (size_t i = 0; i < N; ++i) {
    m[i] = mags[i % 6];
    s[i] = signs[(i / 6 + i) % 6];
  }
  ops->copy_sign(m.data(), s.data(), out.data());
  for (size_t i = 0; i < N; ++i) {
    const float want = std::copysign(m[i], s[i]);
    EXPECT_EQ(std::memcmp(&out[i], &want, sizeof want), 0) << "lane " << i << ": " << out[i] << " vs " << want;
  }
}

// The pack truncates, interleaves r, g, b of each lane, and with Reversed puts
// the pixels in the opposite order; store writes exactly 3 N bytes.
TEST_P(SimdOps, PackRgb8TruncatesInterleavesAndStoresExactlyItsBytes) {
  const std::vector<float> r = iota(0.75f), g = iota(100.5f), b = iota(200.0f);
  for (const bool reversed : {false, true}) {
    std::vector<unsigned char> out(size_t(3 * n + 16), 0xEE);
    ops->pack(r.data(), g.data(), b.data(), reversed, out.data());
    for (int i = 0; i < n; ++i) {
      const int lane = reversed ? n - 1 - i : i;
      EXPECT_EQ(out[size_t(3 * i + 0)], lane) << "pixel " << i << ", reversed " << reversed;
      EXPECT_EQ(out[size_t(3 * i + 1)], 100 + lane) << "pixel " << i << ", reversed " << reversed;
      EXPECT_EQ(out[size_t(3 * i + 2)], 200 + lane) << "pixel " << i << ", reversed " << reversed;
    }
    for (size_t k = size_t(3 * n); k < out.size(); ++k) EXPECT_EQ(out[k], 0xEE) << "byte " << k;
  }
}

TEST_P(SimdOps, ReverseOfIntegersMatchesTheReversedPack) {
  const std::vector<float> r = iota(), g = iota(100.0f), b = iota(200.0f);
  std::vector<unsigned char> want(size_t(3 * n)), got(size_t(3 * n));
  ops->pack(r.data(), g.data(), b.data(), true, want.data());
  ops->reverse_ints_then_pack(r.data(), g.data(), b.data(), got.data());
  EXPECT_EQ(got, want);
}

TEST_P(SimdOps, StoreRgbfInterleavesFloats) {
  const std::vector<float> r = iota(), g = iota(1000.0f), b = iota(2000.0f);
  std::vector<float> out(size_t(3 * n + 4), -7.0f);
  ops->store_rgbf(r.data(), g.data(), b.data(), out.data());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(out[size_t(3 * i + k)], 1000.0f * float(k) + float(i)) << "pixel " << i << ", channel " << k;
  for (size_t k = size_t(3 * n); k < out.size(); ++k) EXPECT_EQ(out[k], -7.0f) << "float " << k;
}

TEST_P(SimdOps, Store4WritesFourPacksSideBySide) {
  if (!ops->store4) GTEST_SKIP() << "no store4 here: the kernel stores one pack at a time";
  std::vector<float> rgb;
  for (int batch = 0; batch < 4; ++batch)
    for (int k = 0; k < 3; ++k)
      for (float x : iota(float(60 * k + 16 * batch))) rgb.push_back(x);
  std::vector<unsigned char> out(size_t(12 * n + 16), 0xEE);
  ops->store4(rgb.data(), out.data());
  for (int batch = 0; batch < 4; ++batch)
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(out[size_t(3 * (n * batch + i) + k)], 60 * k + 16 * batch + i)
            << "batch " << batch << ", pixel " << i << ", channel " << k;
  for (size_t k = size_t(12 * n); k < out.size(); ++k) EXPECT_EQ(out[k], 0xEE) << "byte " << k;
}

TEST_P(SimdOps, StoreFirstWritesOnlyTheFirstPixels) {
  if (!ops->store_first) GTEST_SKIP() << "no byte-masked store here: the kernel stores a row's tail through a stack buffer";
  const std::vector<float> r = iota(), g = iota(100.0f), b = iota(200.0f);
  std::vector<unsigned char> whole(size_t(3 * n));
  ops->pack(r.data(), g.data(), b.data(), false, whole.data());
  for (int count = 1; count < n; ++count) {
    std::vector<unsigned char> out(size_t(3 * n + 16), 0xEE);
    ops->store_first(r.data(), g.data(), b.data(), count, out.data());
    for (size_t k = 0; k < out.size(); ++k)
      EXPECT_EQ(out[k], k < size_t(3 * count) ? whole[k] : 0xEE) << count << " pixels, byte " << k;
  }
}

std::string isa_name(const ::testing::TestParamInfo<isa>& p) {
  return std::string(to_string(p.param.which));
}

// The instruction sets this build compiles for (src/simd/CMakeLists.txt).
const isa compiled_isas[] = {
#if RAYCAST_HAVE_X86_KERNELS
    {backend::sse2, &raycast_test::sse2::ops},
    {backend::avx2, &raycast_test::avx2::ops},
    {backend::avx512, &raycast_test::avx512::ops},
#endif
#if RAYCAST_HAVE_NEON_KERNELS
    {backend::neon, &raycast_test::neon::ops},
#endif
};

INSTANTIATE_TEST_SUITE_P(EveryIsa, SimdOps, ::testing::ValuesIn(compiled_isas), isa_name);

}  // namespace
