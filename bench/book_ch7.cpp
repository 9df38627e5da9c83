#include "book_ch7.h"

#include <cstdlib>
#include <ostream>

namespace raycast::bench {
namespace book {

double random_double() { return rand() / (RAND_MAX + 1.0); }

camera::camera() {
  const double aspect_ratio = 16.0 / 9.0;
  const double viewport_height = 2.0;
  const double viewport_width = aspect_ratio * viewport_height;
  const double focal_length = 1.0;

  origin = point3(0, 0, 0);
  horizontal = vec3(viewport_width, 0.0, 0.0);
  vertical = vec3(0.0, viewport_height, 0.0);
  lower_left_corner = origin - horizontal / 2.0 - vertical / 2.0 - vec3(0, 0, focal_length);
}

hittable_list ch6_world() {
  hittable_list world;
  world.add(std::make_shared<sphere>(point3(0, 0, -1), 0.5));
  world.add(std::make_shared<sphere>(point3(0, -100.5, -1), 100));
  return world;
}

color sample_pixel(const camera& cam, const hittable& world, int i, int j, int image_width,
                   int image_height, int samples_per_pixel) {
  color pixel_color(0, 0, 0);
  for (int s = 0; s < samples_per_pixel; ++s) {
    const double u = (i + random_double()) / (image_width - 1);
    const double v = (j + random_double()) / (image_height - 1);
    const ray r = cam.get_ray(u, v);
    pixel_color += ray_color(r, world);
  }
  return pixel_color;
}

void write_color(std::ostream& out, color pixel_color, int samples_per_pixel) {
  double r = pixel_color.x;
  double g = pixel_color.y;
  double b = pixel_color.z;

  // Divide the color by the number of samples.
  const double scale = 1.0 / samples_per_pixel;
  r *= scale;
  g *= scale;
  b *= scale;

  // Write the translated [0,255] value of each color component.
  out << to_byte(r) << ' ' << to_byte(g) << ' ' << to_byte(b) << '\n';
}

}  // namespace book

book_ch7_image render_book_ch7(int w, int h, int samples_per_pixel, unsigned seed, bool bytes) {
  srand(seed);
  const book::hittable_list world = book::ch6_world();
  const book::camera cam;
  book_ch7_image img;
  img.width = w;
  img.height = h;
  img.rgb.resize(size_t(w) * size_t(h) * 3);
  if (bytes) img.rgb8.resize(img.rgb.size());
  const double scale = 1.0 / samples_per_pixel;
  for (int j = h - 1; j >= 0; --j) {
    const size_t row = size_t(h - 1 - j) * size_t(w) * 3;
    for (int i = 0; i < w; ++i) {
      const color c = scale * book::sample_pixel(cam, world, i, j, w, h, samples_per_pixel);
      for (int k = 0; k < 3; ++k) {
        const size_t at = row + 3 * size_t(i) + size_t(k);
        img.rgb[at] = static_cast<float>(c[k]);
        if (bytes) img.rgb8[at] = static_cast<unsigned char>(book::to_byte(c[k]));
      }
    }
  }
  return img;
}

}  // namespace raycast::bench
