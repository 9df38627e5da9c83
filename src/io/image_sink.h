// Where rendered rows go: a PPM written by raycast itself (ppm.h), or the image module's encoders.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "io/format.h"
#include "io/io_error.h"

namespace raycast::io {

class image_sink {
 public:
  virtual ~image_sink() = default;
  // Rows [y0, y1) of the image, top first, in pixel_format_for(format).
  virtual void write_rows(int64_t y0, int64_t y1, const unsigned char* data, size_t stride) = 0;
  // Completes the image; for a file, renames it into place. Throws io_error.
  virtual void finish() = 0;
};

// A width x height image in `format` at `path`, written atomically (atomic_file.h), after checking
// the destination and loading the image module if the format needs it; "-" is a binary PPM on
// standard output (the caller checks the format: stdout_format_error). Throws io_error naming the
// file ("standard output") and the cause.
std::unique_ptr<image_sink> open_sink(const std::string& path, file_format format, int64_t width, int64_t height);

}  // namespace raycast::io
