// The image file formats raycast writes, and the pixels each one takes.
#pragma once
#include <string>
#include <string_view>

#include "image.h"

namespace raycast::io {

enum class file_format { png, ppm, jpg, tif, exr };

std::string_view to_string(file_format f);  // "png", "ppm", "jpg", "tif", "exr"
bool is_float_format(file_format f);        // EXR carries linear 32-bit float
pixel_format pixel_format_for(file_format f);
std::string_view display_name(file_format f);  // "PNG", "JPEG", "TIFF", ... for messages

// Whether the encoder goes back to earlier bytes (TIFF's directory offsets,
// EXR's line offset table), so the file cannot be a pipe or a terminal.
bool needs_seekable_file(file_format f);

}  // namespace raycast::io
