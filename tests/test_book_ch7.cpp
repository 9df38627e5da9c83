// The bench's ch. 7 peer (bench/book_ch7.h, the book's antialiasing program)
// renders the picture our reference renders, averaged the book's way: each
// pixel is the mean of the colour over the square of viewport points up and
// right of its ch. 6 sample point (src/scene/README.md, "Antialiasing (ch. 7)"). That mean
// is computed here without randomness, from our double reference on a grid
// k times finer, so the peer's only error is its own sampling noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "book_ch7.h"
#include "cases.h"
#include "reference/reference.h"
#include "scene/builtin.h"

namespace {

using raycast::bench::book_ch7_image;
using raycast::bench::render_book_ch7;

constexpr int W = 160, H = 90;

// The box-filtered reference of `world` at W x H: pixel (i, j) is the mean of
// the reference at u = (i + a/k) / (W - 1), v = (j + b/k) / (H - 1), a, b in
// [0, k), which are the pixels (k i + a, k j + b) of a k (W - 1) + 1 by
// k (H - 1) + 1 image (the camera's viewport does not depend on the size).
std::vector<double> box_filtered_reference(int k) {
  const int64_t fw = int64_t(k) * (W - 1) + 1, fh = int64_t(k) * (H - 1) + 1;
  const raycast::scene fine =
      raycast_test::make_scene(raycast_test::sized(fw, fh), {}, *raycast::builtin_spheres("world"));
  std::vector<double> out(size_t(W) * H * 3, 0.0);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      raycast::color sum(0.0);
      for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a)
          sum += raycast::reference_pixel(fine, int64_t(k) * i + a, int64_t(k) * j + b);
      const size_t at = (size_t(H - 1 - j) * W + size_t(i)) * 3;  // rows top first
      for (int c = 0; c < 3; ++c) out[at + size_t(c)] = sum[c] / (k * k);
    }
  return out;
}

TEST(BookCh7, AveragesTheReferencePictureOverEachPixelsSquare) {
  const book_ch7_image img = render_book_ch7(W, H, 64);
  ASSERT_EQ(img.width, W);
  ASSERT_EQ(img.height, H);
  ASSERT_EQ(img.rgb.size(), size_t(W) * H * 3);
  EXPECT_TRUE(img.rgb8.empty());
  const std::vector<double> ref = box_filtered_reference(8);
  double sum = 0, worst = 0;
  size_t worst_at = 0;
  for (size_t n = 0; n < ref.size(); ++n) {
    const double e = std::abs(double(img.rgb[n]) - ref[n]);
    sum += e;
    if (!(e <= worst)) worst = e, worst_at = n;
  }
  const double mean = sum / double(ref.size());
  // Away from the silhouettes a pixel's colour barely changes over its square:
  // only the edge pixels (a few percent) carry the 64 samples' noise.
  EXPECT_LT(mean, 2e-3) << "worst " << worst << " at row " << worst_at / 3 / W << ", column "
                        << worst_at / 3 % W;
  RecordProperty("mean_abs_err", std::to_string(mean));
  // The largest jump (the sphere's underside against the ground: 1 in green)
  // half covered gives a mean of 64 samples a standard deviation of 1/16.
  EXPECT_LT(worst, 0.4) << "at row " << worst_at / 3 / W << ", column " << worst_at / 3 % W;
}

TEST(BookCh7, SameSeedSamePictureAndBytesByWriteColour) {
  const book_ch7_image a = render_book_ch7(32, 18, 4, 7, true);
  const book_ch7_image b = render_book_ch7(32, 18, 4, 7, true);
  const book_ch7_image c = render_book_ch7(32, 18, 4, 8, true);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.rgb8, b.rgb8);
  EXPECT_NE(a.rgb, c.rgb);
  ASSERT_EQ(a.rgb8.size(), a.rgb.size());
  for (size_t n = 0; n < a.rgb.size(); ++n)  // the float is the double mean, rounded
    EXPECT_NEAR(double(a.rgb8[n]), std::min(255.0, std::floor(256.0 * double(a.rgb[n]))), 1.0) << n;
}

TEST(BookCh7, WriteColourScalesBy256AndClamps) {
  using raycast::bench::book::to_byte;
  EXPECT_EQ(to_byte(0.5), 128);  // ch. 4's int(255.999 c) gives 127
  EXPECT_EQ(to_byte(1.0), 255);
  EXPECT_EQ(to_byte(2.0), 255);
  EXPECT_EQ(to_byte(0.0), 0);
  EXPECT_EQ(to_byte(-1.0), 0);
  EXPECT_EQ(to_byte(0.998), 255);
  EXPECT_EQ(to_byte(0.996), 254);
}

}  // namespace
