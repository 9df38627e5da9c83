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

#include <memory>
#include <vector>

#include "io/format.h"
#include "io/movie.h"
#include "library/source.h"
#include "raycast/description.h"

namespace raycast::cli {

using io::file_format;
using io::is_float_format;
using io::to_string;

// A run: what --scene names, open, and the frames to render of it (one for
// a scene; a trajectory's --frames, or all of them), each to an image (a
// pattern's name for each frame) or to one movie.
struct job {
  std::shared_ptr<scene_source> source;
  std::vector<size_t> frames;  // indices in the file, in order; with every_frame, the first two at most
  bool every_frame = false;    // a trajectory without --frames: each frame as it comes, to the file's end
  described_scene first;       // frames[0]'s, described while the options were checked
  std::string output;          // "-": binary PPM on standard output; a pattern f_%05d.png; a movie
  file_format format = file_format::png;
  std::optional<io::movie_kind> movie;
  bool pattern = false;  // output holds the frame's index (printf's %d)
  int fps = 30;
  api::options options;
  api::region region;  // the whole image unless --region
  bool quiet = false;
  bool stats = false;  // --stats: timings and memory on standard error after the run
  bool skip_existing = false;
};

// A refusal of the pipeline in the command line's words ("--width: ...",
// "--scene: FILE: frame 3 (line 12): ..."), and its exit code (1: the file
// could not be read; 2: bad input).
std::string refusal_text(const refusal& r, int& exit_code);

// Frame k's output name: the pattern with k, or the output itself.
std::string output_name(const job& j, size_t k);

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
