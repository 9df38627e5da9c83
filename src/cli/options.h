// Command-line arguments -> a validated job. Every usage error is one line
// naming the option and why; nothing here touches the file system.
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

struct job {
  std::string output;  // "-": binary PPM on standard output
  file_format format = file_format::png;
  scene sc;
  render_options render;
  bool quiet = false;
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

// Strict number parsing, exposed for tests: the whole text must be the number,
// finite and in range; returns an error reason otherwise.
std::optional<std::string> parse_int(std::string_view text, int64_t& value);
std::optional<std::string> parse_real(std::string_view text, double& value);
std::optional<std::string> parse_triple(std::string_view text, vec3& value);
std::optional<std::string> parse_aspect(std::string_view text, double& value);

}  // namespace raycast::cli
