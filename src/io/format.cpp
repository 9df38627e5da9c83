#include "io/format.h"

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
