// Caller-owned pixel memory: a band of rows of an interleaved RGB image,
// rows top first (the lesson's PPM order).
#pragma once
#include <cstddef>
#include <cstdint>

namespace raycast {

enum class pixel_format : uint8_t {
  rgb8,     // 3 bytes per pixel, the lesson's int(255.999 c), clamped
  rgb_f32,  // 3 floats per pixel, linear colour, unquantized
};

constexpr size_t bytes_per_pixel(pixel_format f) { return f == pixel_format::rgb8 ? 3 : 12; }

// Rows [row_begin, row_end) of the image; row 0 is the top row. `data` points
// at the first byte of row_begin, and row r starts at data + (r - row_begin) * stride.
struct image_band {
  void* data = nullptr;
  size_t stride = 0;
  pixel_format format = pixel_format::rgb8;
  int64_t row_begin = 0;
  int64_t row_end = 0;

  unsigned char* row(int64_t r) const {
    return static_cast<unsigned char*>(data) + size_t(r - row_begin) * stride;
  }
};

}  // namespace raycast
