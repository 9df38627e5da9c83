// The book's own ch. 7 program logic as a peer (Ray Tracing in One Weekend
// v3.2.3, InOneWeekend/main.cc and camera.h at the end of ch. 7,
// "Antialiasing"): the ch. 6 world and classes (book_world.h), the book's
// camera class, `samples_per_pixel` rays per pixel jittered by
// `rand() / (RAND_MAX + 1.0)`, the sum scaled by 1/samples and written as
// `int(256 clamp(c, 0, 0.999))`. Double precision, single-threaded, built with
// the project's -O3 and no -march=native, as the ch. 6 peer. book-ch7
// (book_ch7_main.cpp) is the book's whole program built from these pieces.
#pragma once
#include <algorithm>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "book_world.h"

namespace raycast::bench {
namespace book {

// rtweekend.h: a random real in [0, 1), from the C library's rand().
double random_double();

// camera.h: aspect 16/9, viewport height 2, focal length 1, at the origin
// (fixed, whatever the image size).
class camera {
 public:
  camera();
  ray get_ray(double u, double v) const {
    return ray(origin, lower_left_corner + u * horizontal + v * vertical - origin);
  }

 private:
  point3 origin;
  point3 lower_left_corner;
  vec3 horizontal;
  vec3 vertical;
};

// main.cc's world: the small sphere and the ground.
hittable_list ch6_world();

// main.cc's inner loop: the sum of samples_per_pixel jittered samples of pixel
// (i, j), j = 0 the bottom row.
color sample_pixel(const camera& cam, const hittable& world, int i, int j, int image_width,
                   int image_height, int samples_per_pixel);

// color.h: the byte of one channel of the averaged colour.
inline int to_byte(double c) { return static_cast<int>(256 * std::clamp(c, 0.0, 0.999)); }
// color.h: one pixel as the P3 line "r g b".
void write_color(std::ostream& out, color pixel_color, int samples_per_pixel);

}  // namespace book

// The book's ch. 7 image at w x h (its camera stays 16:9), rows top first
// (row 0 is the book's j = h - 1).
struct book_ch7_image {
  int64_t width = 0, height = 0;
  std::vector<float> rgb;           // the averaged linear colour, interleaved RGB
  std::vector<unsigned char> rgb8;  // write_color's bytes; empty unless asked for
};

// Renders the book's way: srand(seed) first, so a run is repeatable (the
// book's program never calls srand: seed 1, the C library's default, gives
// its picture). Pixels are visited, and rand() drawn, in the book's order.
book_ch7_image render_book_ch7(int w, int h, int samples_per_pixel, unsigned seed = 1,
                               bool bytes = false);

}  // namespace raycast::bench
