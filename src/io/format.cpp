#include "io/format.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace raycast::io {

std::string_view to_string(file_format f) {
  switch (f) {
    case file_format::png: return "png";
    case file_format::ppm: return "ppm";
    case file_format::jpg: return "jpg";
    case file_format::tif: return "tif";
    case file_format::exr: return "exr";
  }
  return "?";
}

std::optional<file_format> format_from_name(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (n == "png") return file_format::png;
  if (n == "ppm" || n == "pnm") return file_format::ppm;
  if (n == "jpg" || n == "jpeg") return file_format::jpg;
  if (n == "tif" || n == "tiff") return file_format::tif;
  if (n == "exr") return file_format::exr;
  return std::nullopt;
}

std::optional<std::string> format_from_path(const std::string& path, file_format& format) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "'" + path + "' has no extension; supported: " + std::string(supported_extensions) + " (or use --format)";
  auto f = format_from_name(std::string_view(path).substr(dot + 1));
  if (!f) return "unknown extension '" + path.substr(dot) + "'; supported: " + std::string(supported_extensions);
  format = *f;
  return std::nullopt;
}

bool is_float_format(file_format f) { return f == file_format::exr; }

pixel_format pixel_format_for(file_format f) {
  return is_float_format(f) ? pixel_format::rgb_f32 : pixel_format::rgb8;
}

std::string_view display_name(file_format f) {
  switch (f) {
    case file_format::png: return "PNG";
    case file_format::ppm: return "PPM";
    case file_format::jpg: return "JPEG";
    case file_format::tif: return "TIFF";
    case file_format::exr: return "EXR";
  }
  return "?";
}

int64_t max_side(file_format f) {
  switch (f) {
    case file_format::jpg: return 65500;
    case file_format::png: return 1000000;
    default: return 0;
  }
}

bool needs_seekable_file(file_format f) { return f == file_format::tif || f == file_format::exr; }

}  // namespace raycast::io
