// Each operation of the vector layer (src/simd/) on its own, on every
// target this build has (simd/targets.h: the 1-lane scalar target; x86-64:
// SSE2, AVX2, AVX-512; AArch64: NEON, under qemu in the cross build), against the scalar meaning the kernels
// rely on, so that a wrong reverse, pack or hash step fails here by name
// instead of as a pixel difference somewhere in an image: lane order, packing
// and interleaving, comparisons and masks, max and min with the scalar
// renderer's a > b ? a : b (NaN and signed zeros included, where NEON's own
// fmax differs), arithmetic rounded once per operation, the reciprocal square
// root estimate's accuracy, and the integer lanes (vint: splat, truncating
// conversion, reverse; vuint, the samplers' hashes: wrapping arithmetic, bit
// operations, logical shifts, conversion to float, a float's bits). An
// instruction set this CPU (or RAYCAST_MAX_ISA) cannot run is skipped with the
// reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "backend_test.h"
#include "render/backend.h"
#include "simd_ops/ops.h"

namespace {

using namespace raycast;
using raycast_test::simd_ops;

struct isa {
  backend which;
  const simd_ops* ops;
};
void PrintTo(const isa& i, std::ostream* os) { *os << to_string(i.which); }

class SimdOps : public raycast_test::backend_test<isa> {
 protected:
  void SetUp() override {
    backend_test::SetUp();
    if (IsSkipped()) return;
    ops = GetParam().ops;
    n = ops->lanes;
  }
  // i * step + start in lane i.
  std::vector<float> iota(float start = 0.0f, float step = 1.0f) const {
    std::vector<float> v(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) v[size_t(i)] = start + step * float(i);
    return v;
  }
  // Lane i of call k gets values[(k * n + i) % size]: every value is seen,
  // in every lane position over the calls.
  template <class T>
  std::vector<std::vector<T>> spread(const std::vector<T>& values) const {
    const size_t calls = std::max<size_t>(1, (values.size() + size_t(n) - 1) / size_t(n)) + 1;
    std::vector<std::vector<T>> v(calls, std::vector<T>(static_cast<size_t>(n)));
    for (size_t k = 0; k < calls; ++k)
      for (size_t i = 0; i < size_t(n); ++i) v[k][i] = values[(k * size_t(n) + i + k) % values.size()];
    return v;
  }
  const simd_ops* ops = nullptr;
  int n = 0;
};

uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}
float from_bits(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}
constexpr float nan = std::numeric_limits<float>::quiet_NaN();

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

TEST_P(SimdOps, SelectOfVectorsTakesTheFirstWhereTheLanesAreEqual) {
  const std::vector<float> x = iota(), a = iota(10.0f), b = iota(-10.0f, -1.0f);
  std::vector<float> y(static_cast<size_t>(n)), out(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const float same[] = {float(i), float(i) + 0.5f, nan, i == 0 ? -0.0f : float(i) - 1.0f};
    y[size_t(i)] = same[i % 4];  // equal, not, NaN (never equal), -0 == +0 in lane 0
  }
  ops->select_equal(x.data(), y.data(), a.data(), b.data(), out.data());
  for (size_t i = 0; i < size_t(n); ++i)
    EXPECT_EQ(out[i], x[i] == y[i] ? a[i] : b[i]) << "lane " << i << ": " << x[i] << " == " << y[i];
  EXPECT_EQ(out[0], a[0]);
}

// The scalar renderer's max and min (kernels/scalar.cpp): a > b ? a : b and
// a < b ? a : b, bit for bit: the second operand where either is NaN or both
// are zeros (x86's maxps; NEON builds it from a compare and a bit select).
// clamp(x, lo, hi) is min(max(x, lo), hi): lo for a NaN.
TEST_P(SimdOps, MaxMinAndClampHaveTheScalarRenderersMeaning) {
  const float inf = INFINITY, den = 1e-45f;
  const std::vector<std::pair<float, float>> pairs = {
      {1.0f, 2.0f}, {-0.0f, 0.0f}, {0.0f, -0.0f}, {nan, 1.0f}, {2.0f, nan}, {nan, nan}, {-3.0f, -4.0f},
      {5.0f, 5.0f}, {inf, -inf},  {-inf, inf},   {den, -den},  {-den, 0.0f}, {-nan, -0.0f}, {3e38f, -3e38f},
      {1.5f, -2.0f}, {-1.0f, 0.75f}, {0.25f, 0.5f}};
  for (const std::vector<std::pair<float, float>>& batch : spread(pairs)) {
    std::vector<float> a(static_cast<size_t>(n)), b(static_cast<size_t>(n)), mx(static_cast<size_t>(n)), mn(static_cast<size_t>(n)), cl(static_cast<size_t>(n));
    for (size_t i = 0; i < size_t(n); ++i) std::tie(a[i], b[i]) = batch[i];
    ops->min_max(a.data(), b.data(), -1.0f, 1.0f, mx.data(), mn.data(), cl.data());
    for (size_t i = 0; i < size_t(n); ++i) {
      const float want_max = a[i] > b[i] ? a[i] : b[i], want_min = a[i] < b[i] ? a[i] : b[i];
      const float lo = a[i] > -1.0f ? a[i] : -1.0f, want_clamp = lo < 1.0f ? lo : 1.0f;
      EXPECT_EQ(bits(mx[i]), bits(want_max)) << "max(" << a[i] << ", " << b[i] << "), lane " << i;
      EXPECT_EQ(bits(mn[i]), bits(want_min)) << "min(" << a[i] << ", " << b[i] << "), lane " << i;
      EXPECT_EQ(bits(cl[i]), bits(want_clamp)) << "clamp(" << a[i] << "), lane " << i;
    }
  }
}

// Exact mode needs every operation rounded once, as the scalar renderer's:
// a * b + c in two roundings (never fused, though AVX2, AVX-512 and NEON have
// FMA: -ffp-contract=off, as the kernels), a / sqrt(b) correctly rounded.
TEST_P(SimdOps, ArithmeticRoundsOnceLikeScalarFloat) {
  const std::vector<float> av = {1.1f, 3.0f, 1e-38f, 7.0f, 0.1f, 1e30f, 2.0f, 1.0f / 3.0f, -0.7f, 123456.7f};
  const std::vector<float> bv = {2.3f, 7.0f, 3.0f, 1e-7f, 0.2f, 1e10f, 0.5f, 3.0f, 0.3f, 1e-3f, 2.0f};
  const std::vector<float> cv = {-2.53f, 0.5f, 1.0f, -7.0f, 0.3f, 1e35f, -1.0f, -1.0f, 0.21f};
  const auto as = spread(av), bs = spread(bv), cs = spread(cv);
  for (size_t k = 0; k < std::min({as.size(), bs.size(), cs.size()}); ++k) {
    const std::vector<float>&a = as[k], &b = bs[k], &c = cs[k];
    std::vector<float> mul_add(static_cast<size_t>(n)), div_sqrt(static_cast<size_t>(n));
    ops->arithmetic(a.data(), b.data(), c.data(), mul_add.data(), div_sqrt.data());
    for (size_t i = 0; i < size_t(n); ++i) {
      volatile float p = a[i] * b[i];
      EXPECT_EQ(bits(mul_add[i]), bits(p + c[i])) << a[i] << " * " << b[i] << " + " << c[i] << ", lane " << i;
      EXPECT_EQ(bits(div_sqrt[i]), bits(a[i] / std::sqrt(b[i]))) << a[i] << " / sqrt(" << b[i] << "), lane " << i;
    }
  }
}

// rsqrt_est within the bound the kernel's single biased Newton step was
// designed for, x86's rsqrtps (1.5 * 2^-12); NEON's FRSQRTE + one FRSQRTS step
// (simd/neon.h) is finer: measured 2^-15.9.
TEST_P(SimdOps, RsqrtEstimateIsWithinTheKernelsBound) {
  double worst = 0;
  std::vector<float> x(static_cast<size_t>(n)), got(static_cast<size_t>(n));
  for (uint32_t u = 0x3f800000u; u < 0x40800000u; u += 97) {  // [1, 4): the estimate's period
    for (int k = 0; k < n; ++k) x[size_t(k)] = from_bits(u + uint32_t(k));
    ops->rsqrt_est(x.data(), got.data());
    for (size_t k = 0; k < size_t(n); ++k)
      worst = std::fmax(worst, std::fabs(double(got[k]) * std::sqrt(double(x[k])) - 1.0));
  }
  EXPECT_LT(worst, 1.5 * 0x1p-12);
  if (GetParam().which == backend::neon) {
    EXPECT_LT(worst, 0x1p-15);
  }
  RecordProperty("worst_relative_error_e9", int(worst * 1e9));
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
  const auto at_least_one = [](float x) { return x >= 1.0f; };
  EXPECT_EQ(any_ge, std::any_of(a.begin(), a.end(), at_least_one));  // lanes 0 (0) and 1 (1): 1 lane, false
  EXPECT_EQ(none_ge, std::none_of(a.begin(), a.end(), at_least_one));
  EXPECT_EQ(all_ge, std::all_of(a.begin(), a.end(), at_least_one));
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
  const float mags[] = {0.0f, -0.0f, 1.5f, -2.25f, INFINITY, 3e-42f, nan, -7.0f};
  const float signs[] = {1.0f, -1.0f, 0.0f, -0.0f, -INFINITY, nan, -nan, 3e-42f};
  std::vector<std::pair<float, float>> pairs;  // every magnitude with every sign
  for (float m : mags)
    for (float sg : signs) pairs.push_back({m, sg});
  for (const std::vector<std::pair<float, float>>& batch : spread(pairs)) {
    std::vector<float> m(static_cast<size_t>(n)), sg(static_cast<size_t>(n)), out(static_cast<size_t>(n));
    for (size_t i = 0; i < size_t(n); ++i) std::tie(m[i], sg[i]) = batch[i];
    ops->copy_sign(m.data(), sg.data(), out.data());
    for (size_t i = 0; i < size_t(n); ++i)
      EXPECT_EQ(bits(out[i]), bits(std::copysign(m[i], sg[i])))
          << "lane " << i << ": copysign(" << m[i] << ", " << sg[i] << ") = " << out[i];
  }
}

// The pack truncates, interleaves r, g, b of each lane, and with Reversed puts
// the pixels in the opposite order; store writes exactly 3 N bytes, from any
// address: nothing before or after them changes.
TEST_P(SimdOps, PackRgb8TruncatesInterleavesAndStoresExactlyItsBytes) {
  std::vector<float> r = iota(0.75f), g = iota(100.5f), b = iota(200.0f);
  b[size_t(n - 1)] = 255.999f;  // the largest byte, from the kernel's largest product
  g[0] = 128.0f;                // a high bit alone
  for (const bool reversed : {false, true}) {
    std::vector<unsigned char> buf(size_t(3 * n + 17), 0xEE);
    unsigned char* out = buf.data() + 1;
    ops->pack(r.data(), g.data(), b.data(), reversed, out);
    EXPECT_EQ(buf[0], 0xEE) << "the byte before, reversed " << reversed;
    for (int i = 0; i < n; ++i) {
      const size_t lane = size_t(reversed ? n - 1 - i : i);
      EXPECT_EQ(out[3 * i + 0], int(r[lane])) << "pixel " << i << ", reversed " << reversed;
      EXPECT_EQ(out[3 * i + 1], int(g[lane])) << "pixel " << i << ", reversed " << reversed;
      EXPECT_EQ(out[3 * i + 2], int(b[lane])) << "pixel " << i << ", reversed " << reversed;
    }
    for (size_t k = size_t(3 * n) + 1; k < buf.size(); ++k) EXPECT_EQ(buf[k], 0xEE) << "byte " << k;
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

// ------------------------------------------------------------ integer lanes

const std::vector<int32_t> int_edges = {0, 1, -1, 2, -2, 255, 256, 0x7fff, -0x8000, 0x01020304, -0x01020304,
                                        INT_MAX, INT_MIN, INT_MAX - 1, INT_MIN + 1, 0x55555555, -0x55555556};
const std::vector<uint32_t> uint_edges = {0u,          1u,          2u,          3u,          0xffu,
                                          0x100u,      0xffffu,     0x10000u,    0x7fffffffu, 0x80000000u,
                                          0x80000001u, 0xfffffffeu, 0xffffffffu, 0x9e3779b9u, 0x7feb352du,
                                          0x846ca68bu, 0xdeadbeefu, 0x00ff00ffu, 0x12345678u};

TEST_P(SimdOps, SplatIntFillsEveryLane) {
  std::vector<int32_t> out(static_cast<size_t>(n));
  for (int32_t x : int_edges) {
    ops->splat_int(x, out.data());
    for (size_t i = 0; i < size_t(n); ++i) EXPECT_EQ(out[i], x) << "lane " << i;
  }
}

// to_int truncates toward zero, as int32_t(x) (cvttps2dq, fcvtzs): halves and
// negatives included, up to the largest floats in int32_t's range. (Out of
// range and NaN the instruction sets differ, x86 giving INT_MIN and NEON
// saturating; the kernel converts only values in [0, 256).)
TEST_P(SimdOps, ToIntTruncatesTowardZero) {
  const std::vector<float> values = {
      0.0f,     -0.0f,        0.5f,         -0.5f,        1.5f,          -1.5f,        2.5f,
      -2.5f,    0.999f,       1.0f,         254.999f,     255.999f,      127.5f,       3.99999f,
      200.0f,   -0.999f,      -1.0f,        1e-45f,       -1e-45f,       8388607.5f,   -8388607.5f,
      16777216.0f, 16777218.0f, -16777218.0f, 2147483520.0f, -2147483520.0f, -2147483648.0f, 1e9f};
  for (const std::vector<float>& in : spread(values)) {
    std::vector<int32_t> out(static_cast<size_t>(n));
    ops->to_int(in.data(), out.data());
    for (size_t i = 0; i < size_t(n); ++i) EXPECT_EQ(out[i], int32_t(in[i])) << "to_int(" << in[i] << "), lane " << i;
  }
}

TEST_P(SimdOps, ReverseOfIntegersMirrorsTheLanes) {
  for (const std::vector<int32_t>& in : spread(int_edges)) {
    std::vector<int32_t> out(static_cast<size_t>(n));
    ops->reverse_ints(in.data(), out.data());
    for (size_t i = 0; i < size_t(n); ++i) EXPECT_EQ(out[i], in[size_t(n) - 1 - i]) << "lane " << i;
  }
}

TEST_P(SimdOps, UintSplatAndIota) {
  std::vector<uint32_t> splat(static_cast<size_t>(n)), iota_out(static_cast<size_t>(n));
  for (uint32_t s : uint_edges) {
    ops->uint_splat_iota(s, splat.data(), iota_out.data());
    for (size_t i = 0; i < size_t(n); ++i) {
      EXPECT_EQ(splat[i], s) << "lane " << i;
      EXPECT_EQ(iota_out[i], uint32_t(s + uint32_t(i))) << "iota(" << s << "), lane " << i;  // wraps
    }
  }
}

// + - * wrap modulo 2^32 (SSE2 builds the low 32-bit product from two 64-bit
// ones); ^ & | bit by bit: uint32_t's meaning, on every pair of edge values.
TEST_P(SimdOps, UintArithmeticWrapsLikeUint32) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (uint32_t a : uint_edges)
    for (uint32_t b : uint_edges) pairs.push_back({a, b});
  for (const std::vector<std::pair<uint32_t, uint32_t>>& batch : spread(pairs)) {
    const size_t N = size_t(n);
    std::vector<uint32_t> a(N), b(N), add(N), sub(N), mul(N), x(N), an(N), o(N);
    for (size_t i = 0; i < N; ++i) std::tie(a[i], b[i]) = batch[i];
    ops->uint_arithmetic(a.data(), b.data(), add.data(), sub.data(), mul.data(), x.data(), an.data(), o.data());
    for (size_t i = 0; i < N; ++i) {
      SCOPED_TRACE("a = " + std::to_string(a[i]) + ", b = " + std::to_string(b[i]) + ", lane " + std::to_string(i));
      EXPECT_EQ(add[i], uint32_t(a[i] + b[i]));
      EXPECT_EQ(sub[i], uint32_t(a[i] - b[i]));
      EXPECT_EQ(mul[i], uint32_t(uint64_t(a[i]) * b[i]));
      EXPECT_EQ(x[i], a[i] ^ b[i]);
      EXPECT_EQ(an[i], a[i] & b[i]);
      EXPECT_EQ(o[i], a[i] | b[i]);
    }
  }
}

// >> is logical (zeros in from the left, whatever the top bit), << drops the
// bits shifted out; counts 0 to 31, given at run time and as constants (the
// samplers' hashes shift by constants, which compile to other instructions).
TEST_P(SimdOps, UintShiftsAreLogical) {
  const size_t N = size_t(n);
  for (const std::vector<uint32_t>& a : spread(uint_edges)) {
    std::vector<uint32_t> shr(N), shl(N), shr_k(32 * N), shl_k(32 * N);
    ops->uint_shift_constants(a.data(), shr_k.data(), shl_k.data());
    for (int c = 0; c < 32; ++c) {
      ops->uint_shift(a.data(), c, shr.data(), shl.data());
      for (size_t i = 0; i < N; ++i) {
        const uint32_t want_shr = a[i] >> c, want_shl = uint32_t(a[i] << c);
        EXPECT_EQ(shr[i], want_shr) << a[i] << " >> " << c << ", lane " << i;
        EXPECT_EQ(shl[i], want_shl) << a[i] << " << " << c << ", lane " << i;
        EXPECT_EQ(shr_k[size_t(c) * N + i], want_shr) << a[i] << " >> constant " << c << ", lane " << i;
        EXPECT_EQ(shl_k[size_t(c) * N + i], want_shl) << a[i] << " << constant " << c << ", lane " << i;
      }
    }
  }
}

// to_float of lanes below 2^31 (the samplers convert 24 bits at most): exact
// below 2^24, rounded to nearest, ties to even, above, as float(uint32_t).
TEST_P(SimdOps, UintToFloatRoundsToNearestEven) {
  const std::vector<uint32_t> values = {0u,         1u,          0xffffu,     0x10000u,    0xffffffu,
                                        0x1000000u, 0x1000001u,  0x1000002u,  0x1000003u,  0x7fffffbfu,
                                        0x7fffffc0u, 0x7fffffc1u, 0x7fffffffu, 0x12345678u, 0x2000003u};
  for (const std::vector<uint32_t>& in : spread(values)) {
    std::vector<float> out(static_cast<size_t>(n));
    ops->uint_to_float(in.data(), out.data());
    for (size_t i = 0; i < size_t(n); ++i)
      EXPECT_EQ(bits(out[i]), bits(float(in[i]))) << "to_float(" << in[i] << "), lane " << i;
  }
}

// as_uint and as_float move bits, not values: NaN payloads, signed zeros and
// subnormals come back as they went.
TEST_P(SimdOps, FloatBitsRoundTrip) {
  const std::vector<uint32_t> patterns = {0x00000000u, 0x80000000u, 0x3f800000u, 0xbf800000u, 0x00000001u,
                                          0x807fffffu, 0x7f7fffffu, 0x7f800000u, 0xff800000u, 0x7fc00000u,
                                          0xffc00001u, 0x7fa00000u, 0x5f375a86u, 0x12345678u};
  for (const std::vector<uint32_t>& p : spread(patterns)) {
    std::vector<float> in(static_cast<size_t>(n)), back(static_cast<size_t>(n));
    std::vector<uint32_t> got(static_cast<size_t>(n));
    for (size_t i = 0; i < size_t(n); ++i) in[i] = from_bits(p[i]);
    ops->float_bits(in.data(), got.data(), back.data());
    for (size_t i = 0; i < size_t(n); ++i) {
      EXPECT_EQ(got[i], p[i]) << "lane " << i;
      EXPECT_EQ(bits(back[i]), p[i]) << "lane " << i;
    }
  }
}

// Unsigned comparison over the whole 32-bit range (the top bit set on
// either side, equal lanes), and the vuint select it drives (the closest hit's
// sphere indices).
TEST_P(SimdOps, UintCompareIsUnsignedAndSelects) {
  const std::vector<std::pair<uint32_t, uint32_t>> pairs = {
      {0u, 0u}, {1u, 0u}, {0u, 1u}, {0x7fffffffu, 0x80000000u}, {0x80000000u, 0x7fffffffu},
      {0xffffffffu, 0u}, {0u, 0xffffffffu}, {0xfffffffeu, 0xffffffffu}, {5u, 5u}, {0x80000001u, 0x80000000u}};
  std::vector<uint32_t> a, b;
  for (auto [x, y] : pairs) a.push_back(x), b.push_back(y);
  const std::vector<std::vector<uint32_t>> as = spread(a), bs = spread(b);
  for (size_t v = 0; v < as.size(); ++v) {
    std::vector<uint32_t> greater(static_cast<size_t>(n)), larger(static_cast<size_t>(n));
    ops->uint_compare_select(as[v].data(), bs[v].data(), greater.data(), larger.data());
    for (size_t i = 0; i < size_t(n); ++i) {
      EXPECT_EQ(greater[i], as[v][i] > bs[v][i] ? 1u : 0u) << as[v][i] << " > " << bs[v][i] << ", lane " << i;
      EXPECT_EQ(larger[i], std::max(as[v][i], bs[v][i])) << "lane " << i;
    }
  }
}

std::string isa_name(const ::testing::TestParamInfo<isa>& p) {
  return std::string(to_string(p.param.which));
}

// The targets this build compiles for (simd/targets.h), the 1-lane one included.
const isa compiled_isas[] = {
#define RAYCAST_COMPILED(name, arch, lanes, needs, flags) RAYCAST_ON_##arch({backend::name, &raycast_test::name::ops}, )
    RAYCAST_TARGETS(RAYCAST_COMPILED)
#undef RAYCAST_COMPILED
};

INSTANTIATE_TEST_SUITE_P(EveryIsa, SimdOps, ::testing::ValuesIn(compiled_isas), isa_name);

}  // namespace
