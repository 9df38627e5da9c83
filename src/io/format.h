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

// The one table of format names (--format, a file's extension, the
// library's and Python's format=): each format's own name first, then its
// other spellings.
struct format_name {
  std::string_view name;
  file_format format;
};
inline constexpr format_name format_names[] = {
    {"png", file_format::png}, {"ppm", file_format::ppm}, {"pnm", file_format::ppm},
    {"jpg", file_format::jpg}, {"jpeg", file_format::jpg}, {"tif", file_format::tif},
    {"tiff", file_format::tif}, {"exr", file_format::exr},
};
// Every name in the table, in its order: what --format accepts.
std::span<const std::string_view> format_name_list();

std::string_view to_string(file_format f);  // its own name: "png", "ppm", "jpg", "tif", "exr"
// The format a name or file extension means, any case; nullopt for another.
std::optional<file_format> format_from_name(std::string_view name);
// "png, ppm, pnm, jpg, ..." (or with another separator), for messages and --help.
std::string format_names_text(std::string_view separator = ", ");
// The format a file name's extension gives ("-", standard output: PPM), or
// why there is none (no extension, an unknown one); the reason is a
// sentence for "--output: ".
std::optional<std::string> format_from_path(const std::string& path, file_format& format);
// "-" names standard output wherever a path is taken: it takes binary PPM
// only. Why format cannot go there, or nullopt.
std::optional<std::string> stdout_format_error(file_format f);
// What a file name's extension supports, for messages: ".png, .ppm, .pnm, ...".
std::string supported_extensions();
bool is_float_format(file_format f);        // EXR carries linear 32-bit float
pixel_format pixel_format_for(file_format f);
std::string_view display_name(file_format f);  // "PNG", "JPEG", "TIFF", ... for messages

// The longest side each format's encoder accepts: libjpeg's 65500 (JPEG's
// 16-bit sizes), libpng's default user limit of 1,000,000; the others take
// anything up to raycast's own limit (this returns 0). Checked before
// anything is written, so the libraries never get to refuse (libjpeg would
// print and exit() itself).
int64_t max_side(file_format f);

// Whether the encoder goes back to earlier bytes (TIFF's directory offsets,
// EXR's line offset table), so the file cannot be a pipe or a terminal.
bool needs_seekable_file(file_format f);

}  // namespace raycast::io
