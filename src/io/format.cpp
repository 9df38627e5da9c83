#include "io/format.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

namespace raycast::io {

std::span<const std::string_view> format_name_list() {
  static const auto names = [] {
    std::array<std::string_view, std::size(format_names)> n{};
    for (size_t k = 0; k < n.size(); ++k) n[k] = format_names[k].name;
    return n;
  }();
  return names;
}

std::string_view to_string(file_format f) {
  for (const format_name& n : format_names)
    if (n.format == f) return n.name;
  return "?";
}

std::optional<file_format> format_from_name(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const format_name& f : format_names)
    if (f.name == n) return f.format;
  return std::nullopt;
}

std::string supported_extensions() {
  std::string r;
  for (const format_name& f : format_names) r += (r.empty() ? "." : ", .") + std::string(f.name);
  return r;
}

std::optional<std::string> stdout_format_error(file_format f) {
  if (f == file_format::ppm) return std::nullopt;
  return "standard output takes ppm only, got " + std::string(to_string(f));
}

std::optional<std::string> format_from_path(const std::string& path, file_format& format) {
  if (path == "-") {
    format = file_format::ppm;
    return std::nullopt;
  }
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "'" + path + "' has no extension; supported: " + supported_extensions() + " (or use --format)";
  auto f = format_from_name(std::string_view(path).substr(dot + 1));
  if (!f) return "unknown extension '" + path.substr(dot) + "'; supported: " + supported_extensions();
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
