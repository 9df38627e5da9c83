// The run pipeline every front end calls: a layer of settings (the command
// line's options, Python's keywords) over the scene --scene names, read,
// merged, resolved and checked into a description (raycast/description.h),
// with refusals that say who gave the value and where, for each front end
// to word in its own terms.
#pragma once
#include <cstdint>
#include <string>

#include "io/format.h"
#include "render/render.h"
#include "raycast/raycast.h"
#include "settings/layer.h"
#include "settings/resolve.h"

namespace raycast {

// How a front end names a setting in its errors: the command line by its
// option ("--width"), the library and Python by the scene file's key
// ("camera.width") or the keyword ("threads").
enum class front_end : uint8_t { command_line, library };
std::string spell(const setting& row, front_end fe);

// A refusal with its parts: who gave the value as they spelled it ("" for a
// scene file as a whole), the scene file it is in ("" for none), and why.
using error_kind = enum api::error::kind;
struct refusal {
  error_kind kind = error_kind::invalid_argument;
  std::string source;
  std::string file;
  std::string why;
};
// The library's and Python's words for it: field = source ("scene" for a
// whole file), message = "FILE: why" where a file is to blame.
api::error library_error(const refusal& r);
refusal refused(const setting_error& e, std::string file = "");

// The format of an output at path: format_name's (a row's name, checked) or
// its extension's; "-" (standard output) takes PPM only.
io::file_format output_format(const std::string& path, const std::string& format_name, front_end fe);

// The options' region within a width x height image (the whole image
// unless set), and the sides the output's format can hold.
api::region output_region(const api::options& o, int64_t width, int64_t height, front_end fe);
// What the command line blames for a side too long: --region where given,
// else --width, or --height where given, else --aspect (a derived height).
struct side_blame {
  bool region = false, height = false;
};
void check_sides(io::file_format f, const api::region& r, const side_blame& blame, front_end fe);

// The options as the renderer takes them, each name checked by its row
// (throws api::error: a name or number the row refuses, a backend this CPU
// or build cannot run).
render_options renderer_options(const api::options& o);

}  // namespace raycast
