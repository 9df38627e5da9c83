// Binary PPM (P6), 8-bit: written by raycast itself, no image library loaded.
#pragma once
#include <memory>
#include <string>

#include "io/files/atomic_file.h"
#include "io/image_sink.h"

namespace raycast::io {

// Header and pixels, in bytes.
uint64_t ppm_file_size(int64_t width, int64_t height);

// Writes to fd (the header at once), errors under `name`; commits `file`, if any, at the end.
std::unique_ptr<image_sink> make_ppm_sink(int fd, std::string name, int64_t width, int64_t height,
                                          std::unique_ptr<atomic_file> file);

}  // namespace raycast::io
