// A layer of settings (usually a scene file's keys with a front end's layer
// merged over them) resolved into the description of a render
// (raycast/description.h), and the description's own values checked against
// the input table's rows -- the one place both happen, for every front end.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "raycast/description.h"
#include "scene/invalid.h"
#include "settings/layer.h"

namespace raycast {

// The scene's rows applied to the description's camera, sky and light (the
// values not given keep theirs), ranges checked, derived settings computed
// from the merged values only: a vup without a lookat looks down -z from the
// merged lookfrom; vfov and focal_length mean nothing for an orthographic
// camera. The camera's and the light's own rules (validate()) come after.
std::optional<setting_error> resolve_scene(const settings& s, api::scene& d);

// How particle data become spheres (api::particles), or the first refused
// and why: one that applies to particle files only (all but radius and
// shade, which set every sphere's) where the scene is not one, a colormap or
// range without color_by.
// particle_file: whether the scene is one; keywords: a message names the
// keywords (color_by), not the options (--color-by).
std::optional<setting_error> resolve_particles(const settings& s, bool particle_file, api::particles& p,
                                               bool keywords = false);

// The run's rows: how to render (api::options: backend, precision, threads,
// samples, sampler, seed, region, format) and the command line's own.
struct run_settings {
  api::options options;
  std::string output;  // "-": standard output
  std::optional<std::string> scene;  // --scene's name or path; none: the lesson's sky
  bool quiet = false, stats = false;
};
std::optional<setting_error> resolve_run(const settings& s, run_settings& r);

// The description's values in the input table's terms, for a caller that
// filled the structs itself: each is what its row accepts (a name from the
// row's list, a number within its range). The error names the row's keyword.
std::optional<setting_error> check_options(const api::options& o);
std::optional<setting_error> check_particles(const api::particles& p);

// Who set the field a scene's check refused (scene/scene.h's validate): the
// row that sets it (of the camera position's two, the one given), and
// whether a scene file gave it -- a field no setting gave (a sphere's, the
// count of spheres) is the file's when there is one. merged: the file's keys
// with the other front end's settings over them.
struct blamed {
  setting_id id;
  bool from_file;
};
blamed blame(const invalid_field& e, const settings& merged, bool have_file);

}  // namespace raycast
