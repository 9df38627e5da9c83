// Command-line arguments -> a validated job. Every usage error is one line
// naming the option and why; the only file touched is a --scene file, read
// by the scene room (formats/json.h). The options are the input table's
// (settings/inputs.h), parsed by its parsers (settings/settings.h).
#pragma once
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "io/format.h"
#include "render/render.h"

namespace raycast::cli {

using io::file_format;
using io::is_float_format;
using io::to_string;

// A window of the image: columns [x0, x1), rows [y0, y1), row 0 at the top.
struct pixel_region {
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int64_t width() const { return x1 - x0; }
  int64_t height() const { return y1 - y0; }
};

struct job {
  std::string output;  // "-": binary PPM on standard output
  file_format format = file_format::png;
  scene sc;
  render_options render;
  pixel_region region;  // the whole image unless --region
  bool quiet = false;
  bool stats = false;         // --stats: timings and memory on standard error after the run
  double load_seconds = 0.0;  // reading and parsing the scene file, if any
};

// Either a job to run, or the exit code to leave with: 0 after --help or
// --version, 2 after a usage error (already printed to err).
struct parse_result {
  std::optional<job> run;
  int exit_code = 0;
};

parse_result parse_args(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

// Text with control characters written as \xNN: an error message is one line
// even when a file name holds a line break.
std::string printable(std::string_view s);

}  // namespace raycast::cli
