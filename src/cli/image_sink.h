// Where rendered rows go: a binary PPM written by raycast itself, or a PNG,
// JPEG, TIFF or EXR encoded by the image module (loaded on first use).
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "image.h"
#include "options.h"

namespace raycast::cli {

class image_sink {
 public:
  virtual ~image_sink() = default;
  // Rows [y0, y1) of the image, top first, in the job's pixel format.
  virtual void write_rows(int64_t y0, int64_t y1, const unsigned char* data, size_t stride) = 0;
  // Completes the image; for a file, renames it into place. Throws io_error.
  virtual void finish() = 0;
};

// Opens the sink for the job: checks the destination and loads the image module
// when the format needs it. Throws io_error naming the file and the cause.
std::unique_ptr<image_sink> open_sink(const job& j);

pixel_format sink_pixel_format(const job& j);

}  // namespace raycast::cli
