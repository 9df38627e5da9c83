// Command-line arguments -> a described run. Every usage error is one line
// naming the option and why; the only file touched is a --scene file, read
// through the formats room's registry. The options are the input table's
// (settings/table.h), parsed into a layer of settings and run through the
// pipeline the library and Python share (library/pipeline.h).
#pragma once
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "io/format.h"
#include "raycast/description.h"

namespace raycast::cli {

using io::file_format;
using io::is_float_format;
using io::to_string;

struct job {
  std::string output;  // "-": binary PPM on standard output
  file_format format = file_format::png;
  api::scene description;
  api::options options;
  api::region region;  // the whole image unless --region
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
