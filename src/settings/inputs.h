// The whole input table (settings/settings.h): the scene's rows (camera and
// sky, also a scene file's keys), then the run's (output, format, backend,
// samples, ...), whose names come from their own rooms: backends and
// precisions from render/backend.h, samplers from scene/sampler.h, formats
// from io/format.h. The command line is built from it (cli/options.cpp);
// the library and the Python module check their options with its rows.
#pragma once
#include <span>
#include <string>

#include "raycast/raycast.h"
#include "scene/invalid.h"
#include "formats/ply.h"
#include "settings/settings.h"

namespace raycast {

std::span<const setting> input_table();

// The particle options given (--radius, --color-by, --colormap,
// --color-range; ranges checked already), or the first refused and why: any
// of them for a scene that is not a .ply file, a colormap or range without
// --color-by. scene_name: --scene's value ("" for none); keywords: name the
// library's keywords (color_by) rather than the options (--color-by).
struct particle_settings {
  particle_options options;
  const setting* refused = nullptr;
  std::string why;
};
particle_settings particles_of(const settings& s, std::string_view scene_name, bool keywords = false);
const setting& input_row(setting_id id);

// Who set the field a scene's check refused (scene/scene.h's validate): the
// row that sets it (of the camera position's two, the one given), and whether
// a scene file gave it -- a field no setting gave (a sphere's, the count of
// spheres) is the file's when there is one. merged: the file's keys with the
// other front end's settings over them.
struct blamed {
  setting_id id;
  bool from_file;
};
blamed blame(const invalid_field& e, const settings& merged, bool have_file);

}  // namespace raycast

namespace raycast::api {

// A scene -- kind "name" (as the command line's --scene: a built-in name or
// a .json file, anything else refused with the built-in names), "json" (a
// scene file's text) or "" (the sky alone) -- with settings merged over its
// camera and sky keys before they are resolved, as the command line's
// options over a scene file: the Python module's keywords (errors name the
// scene file's key).
scene scene_with(const std::string& kind, const std::string& source, const settings& over);

}  // namespace raycast::api
