// book-ch7: Ray Tracing in One Weekend's whole program at the end of ch. 7
// (v3.2.3 InOneWeekend/main.cc), built from the peer's pieces (book_ch7.h):
// 400x225, 100 samples per pixel, the P3 PPM on standard output and the
// scanline count on standard error, exactly as the book's. The yardstick of
// bench/aa_end_to_end.sh.
#include <iostream>

#include "book_ch7.h"

using namespace raycast;
using namespace raycast::bench::book;

int main() {
  // Image
  const auto aspect_ratio = 16.0 / 9.0;
  const int image_width = 400;
  const int image_height = static_cast<int>(image_width / aspect_ratio);
  const int samples_per_pixel = 100;

  // World
  const hittable_list world = ch6_world();

  // Camera
  const raycast::bench::book::camera cam;

  // Render
  std::cout << "P3\n" << image_width << ' ' << image_height << "\n255\n";

  for (int j = image_height - 1; j >= 0; --j) {
    std::cerr << "\rScanlines remaining: " << j << ' ' << std::flush;
    for (int i = 0; i < image_width; ++i) {
      const color pixel_color =
          sample_pixel(cam, world, i, j, image_width, image_height, samples_per_pixel);
      write_color(std::cout, pixel_color, samples_per_pixel);
    }
  }

  std::cerr << "\nDone.\n";
}
