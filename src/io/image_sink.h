// Where rendered rows go: a binary PPM written by raycast itself (ppm.h), or a
// PNG, JPEG, TIFF or EXR encoded by the image module (module_loader.h). The
// caller says where, in which format and how large; nothing here knows the
// command line.
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

// A width x height image in `format` at `path`, written atomically
// (atomic_file.h). Checks the destination and loads the image module when the
// format needs it. Throws io_error naming the file and the cause.
std::unique_ptr<image_sink> open_file_sink(const std::string& path, file_format format,
                                           int64_t width, int64_t height);

// A binary PPM on standard output (errors name "standard output").
std::unique_ptr<image_sink> open_stdout_sink(int64_t width, int64_t height);

// Where a path is taken, "-" is standard output (format: PPM, checked by the
// caller, format.h's stdout_format_error); any other path, a file.
std::unique_ptr<image_sink> open_sink(const std::string& path, file_format format, int64_t width, int64_t height);

}  // namespace raycast::io
