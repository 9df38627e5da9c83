// Helpers shared by the tests: whole images in memory, rendered by the
// renderer or straight through one backend, and comparisons that say where
// two images differ. (Scenes and modes: cases.h; error against the
// reference: reference_errors.h, which the bench uses too.)
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "reference_errors.h"
#include "render/render.h"
#include "cases.h"
#include "error_bounds.h"
#include "kernels/scalar.h"

namespace raycast_test {

// Test-name suffixes for tests over backends and modes.
inline std::string backend_name(const ::testing::TestParamInfo<raycast::backend>& i) {
  return std::string(to_string(i.param));
}
inline std::string mode_name(const ::testing::TestParamInfo<mode>& i) { return name_of(i.param); }

// An interleaved RGB image, rows top first, rows packed (stride = 3 channels).
struct image {
  int64_t width = 0, height = 0;
  raycast::pixel_format format = raycast::pixel_format::rgb8;
  std::vector<unsigned char> bytes;

  image() = default;
  image(int64_t w, int64_t h, raycast::pixel_format f)
      : width(w), height(h), format(f),
        bytes(size_t(w) * size_t(h) * raycast::bytes_per_pixel(f), 0xCD) {}

  size_t stride() const { return size_t(width) * raycast::bytes_per_pixel(format); }
  raycast::image_band band() {
    return raycast::image_band{bytes.data(), stride(), format, 0, height};
  }
  // Channel k of the pixel in output row `row` (0 = top), column `col`.
  int byte(int64_t row, int64_t col, int k) const {
    return bytes[size_t(row) * stride() + size_t(col) * 3 + size_t(k)];
  }
  float value(int64_t row, int64_t col, int k) const {
    float f = 0;
    std::memcpy(&f, bytes.data() + size_t(row) * stride() + size_t(col) * 12 + size_t(k) * 4,
                sizeof f);
    return f;
  }
};

inline image render_with(const raycast::renderer& r, raycast::pixel_format f) {
  const raycast::camera& c = r.cam();
  image img(c.image_width, c.image_height, f);
  r.render(img.band());
  return img;
}

inline image render_with_reference(const raycast::scene& s, raycast::pixel_format f) {
  image img(s.cam.image_width, s.cam.image_height, f);
  raycast::render_reference(s, img.band());
  return img;
}

inline image render_with_scalar(const raycast::scene& s, raycast::precision p, raycast::pixel_format f,
                                size_t sort_from = raycast::sorted_from) {
  raycast::render_options o;
  o.which = raycast::backend::scalar;  // the 1-lane target, with no shortcut and no culling
  o.prec = p;
  o.threads = 1;
  o.shortcuts = raycast::shortcut::none;
  o.sort_from = sort_from;
  return render_with(raycast::renderer(s, o), f);
}

// The largest difference between two images of the same size and format, and
// the first place it occurs.
struct difference {
  double max = 0;
  int64_t row = -1, col = -1;
  int channel = -1;
  bool same_shape = true;

  std::string where() const {
    if (!same_shape) return "images differ in size or format";
    return "max difference " + std::to_string(max) + " at row " + std::to_string(row) +
           ", column " + std::to_string(col) + ", channel " + std::to_string(channel);
  }
};

inline difference compare(const image& a, const image& b) {
  difference d;
  if (a.width != b.width || a.height != b.height || a.format != b.format ||
      a.bytes.size() != b.bytes.size()) {
    d.same_shape = false;
    d.max = INFINITY;
    return d;
  }
  for (int64_t r = 0; r < a.height; ++r)
    for (int64_t c = 0; c < a.width; ++c)
      for (int k = 0; k < 3; ++k) {
        double x = 0;
        if (a.format == raycast::pixel_format::rgb8) {
          x = std::abs(a.byte(r, c, k) - b.byte(r, c, k));
        } else {
          const float fa = a.value(r, c, k), fb = b.value(r, c, k);
          x = std::isfinite(fa) && std::isfinite(fb) ? std::abs(double(fa) - double(fb)) : INFINITY;
        }
        if (x > d.max) {
          d.max = x;
          d.row = r;
          d.col = c;
          d.channel = k;
        }
      }
  return d;
}

// Largest |float output - reference_pixel| over the image (an rgb_f32 image),
// measured as the bench measures it (reference_errors.h).
inline difference compare_to_reference_pixels(const image& a, const raycast::scene& s) {
  std::vector<float> values(a.bytes.size() / sizeof(float));
  std::memcpy(values.data(), a.bytes.data(), values.size() * sizeof(float));
  error_stats e;
  reference_band(s, 0, a.height).compare(values.data(), nullptr, e);
  difference d;
  d.max = e.max_abs_err;
  d.row = e.max_abs_err > 0 ? e.worst_row : -1;
  d.col = e.max_abs_err > 0 ? e.worst_col : -1;
  d.channel = e.max_abs_err > 0 ? e.worst_channel : -1;
  return d;
}

}  // namespace raycast_test
