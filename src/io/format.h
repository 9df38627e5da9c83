// The image file formats raycast writes, and the pixels each one takes.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "image/image.h"

namespace raycast::io {

enum class file_format { png, ppm, jpg, tif, exr };

// The one table of format names (--format, extensions, format=): each format's own name first.
struct format_name {
  std::string_view name;
  file_format format;
};
inline constexpr format_name format_names[] = {
    {"png", file_format::png}, {"ppm", file_format::ppm}, {"pnm", file_format::ppm},
    {"jpg", file_format::jpg}, {"jpeg", file_format::jpg}, {"tif", file_format::tif},
    {"tiff", file_format::tif}, {"exr", file_format::exr},
};
// Every name in the table, in order: what --format accepts.
std::span<const std::string_view> format_name_list();

std::string_view to_string(file_format f);  // its own name: "png", "ppm", "jpg", "tif", "exr"
// The format a name or file extension means, any case; nullopt for another.
std::optional<file_format> format_from_name(std::string_view name);
// The format a file name's extension gives ("-": PPM), or why there is none (for "--output: ").
std::optional<std::string> format_from_path(const std::string& path, file_format& format);
// Why format cannot go to standard output ("-", binary PPM only), or nullopt.
std::optional<std::string> stdout_format_error(file_format f);
// What a file name's extension supports, for messages: ".png, .ppm, .pnm, ...".
std::string supported_extensions();
bool is_float_format(file_format f);        // EXR carries linear 32-bit float
pixel_format pixel_format_for(file_format f);
std::string_view display_name(file_format f);  // "PNG", "JPEG", "TIFF", ... for messages

// The longest side the format's encoder accepts (JPEG 65500, libpng's default 1,000,000; 0: no
// limit but raycast's), checked before anything is written (libjpeg would exit() itself).
int64_t max_side(file_format f);
// Whether the encoder goes back to earlier bytes (TIFF, EXR): no pipe or terminal.
bool needs_seekable_file(file_format f);

}  // namespace raycast::io
