// Caller-owned pixel memory: a band of rows of an interleaved RGB image, rows top first.
#pragma once
#include <cstddef>
#include <cstdint>

namespace raycast {

enum class pixel_format : uint8_t {
  rgb8,     // 3 bytes per pixel, the lesson's int(255.999 c), clamped
  rgb_f32,  // 3 floats per pixel, linear colour, unquantized
};

constexpr size_t bytes_per_pixel(pixel_format f) { return f == pixel_format::rgb8 ? 3 : 12; }

// Rows [row_begin, row_end) of the image (0 at the top), columns [col_begin, col_end) of each
// (col_end < 0: to the last). Row r starts at data + (r - row_begin) * stride, at column col_begin.
struct image_band {
  void* data = nullptr;
  size_t stride = 0;
  pixel_format format = pixel_format::rgb8;
  int64_t row_begin = 0;
  int64_t row_end = 0;
  int64_t col_begin = 0;
  int64_t col_end = -1;

  unsigned char* row(int64_t r) const {
    return static_cast<unsigned char*>(data) + size_t(r - row_begin) * stride;
  }
  int64_t cols_end(int64_t width) const { return col_end < 0 ? width : col_end; }
  bool whole_rows(int64_t width) const { return col_begin == 0 && cols_end(width) == width; }
  unsigned char* pixel(int64_t r, int64_t i) const {
    return row(r) + size_t(i - col_begin) * bytes_per_pixel(format);
  }
};

}  // namespace raycast
