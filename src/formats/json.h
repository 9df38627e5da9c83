// Scene files (`--scene FILE.json`): a camera, a sky and spheres as JSON.
//
//   {"camera": {"width": 400, "height": 225, "aspect": 1.7778 or "16:9",
//               "lookfrom": [x,y,z], "lookat": [x,y,z], "vup": [x,y,z],
//               "vfov": 90, "viewport_height": 2, "focal_length": 1},
//    "sky": {"bottom": [r,g,b], "top": [r,g,b]},
//    "spheres": [{"center": [x,y,z], "radius": r, "shade": "normal"},
//                {"center": [x,y,z], "radius": r, "shade": "flat", "color": [r,g,b]}]}
//
// Every key is optional (the lesson's defaults; "shade" defaults to "normal",
// "color" is required for "flat"). Unknown keys, duplicate keys, wrong types,
// numbers beyond a double and invalid spheres are errors naming the JSON path
// ("spheres[3].radius"), with where in the text ("at line 4, column 17") and
// a short quote of it (at most 32 bytes, "…" when cut). Text that is not JSON
// is an error of the whole file (empty path), with the same place when known.
// The camera and sky keys are the input table's (settings/settings.h), parsed by
// its parsers, so a value is spelled as on the command line ("aspect": "16:9"
// or "1.5" or 1.5). read_scene_file returns them unapplied, for a caller to
// merge its own settings over (the CLI's options) before resolve() checks
// their ranges and derives the rest; the camera is checked by validate()
// after, and path() of its error is the JSON path too.
//
// The text is streamed with simdjson's On-Demand API straight into
// scene_params: no document tree. While parsing, memory is the text (padded)
// and simdjson's index of it, both freed before returning; a file of
// windowed_from bytes or more is read and indexed a window at a time instead
// (read_scene_text), so memory is the spheres and two windows.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "scene/scene.h"
#include "settings/layer.h"
#include "settings/resolve.h"

namespace raycast {

struct scene_file_error {
  std::string path;     // "camera.vfov", "spheres[3].radius"; empty for the whole file
  std::string message;  // why
  bool io = false;      // the file could not be read (an I/O failure, not bad input)
};

// A scene file as read: its spheres (scene.spheres; camera and sky as the
// lesson's) and its camera and sky keys, not applied yet.
struct scene_file_contents {
  api::scene scene;
  settings keys;
};

// The largest scene file (4 GiB - 1 byte; simdjson indexes with 32-bit
// offsets): about 45 million spheres at 90 bytes each. Larger files are
// refused before any is read.
inline constexpr uint64_t max_scene_file_bytes = (uint64_t(1) << 32) - 1;

// Parses the text of a scene file and validates its spheres. The text is
// copied into a padded buffer first, or, from windowed_from bytes on, read
// as read_scene_windows does, which gives the same result without an index
// of all of it (and parses the whole text when it gives up).
inline constexpr size_t windowed_from = size_t(1) << 20;
std::variant<scene_file_contents, scene_file_error> read_scene_text(std::string_view text);

// The spheres array parsed a window of about `window` bytes at a time (each
// run of whole spheres indexed and parsed on its own), then the rest of the
// text; nullopt where it gives up (any error, or a layout it does not
// follow: the "spheres" key beyond the text's first 64 KiB, escapes in it).
std::optional<scene_file_contents> read_scene_windows(std::string_view text, size_t window);

// The same, with the file's keys resolved (ranges checked; as on the command
// line, a "vup" without "lookat" looks down -z from "lookfrom").
std::variant<api::scene, scene_file_error> parse_scene_file(std::string_view text);

// Reads the file and parses it as read_scene_text does. Only a regular file
// is read: a directory, device, FIFO or socket is refused without blocking
// (stat, then open with O_NONBLOCK and fstat), as is a file larger than
// max_scene_file_bytes or one that grows while it is read (memory stays at
// the size fstat gave). Errors of the file itself have an empty path and
// strerror's text ("No such file or directory") or the reason.
std::variant<scene_file_contents, scene_file_error> read_scene_file(const std::string& path);
// The same, resolved as parse_scene_file does.
std::variant<api::scene, scene_file_error> load_scene_file(const std::string& path);

}  // namespace raycast
