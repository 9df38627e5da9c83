#include "settings/inputs.h"

#include <memory>
#include <string>
#include <vector>

#include "io/format.h"
#include "render/backend.h"
#include "render/render.h"
#include "scene/builtin.h"
#include "scene/colormap.h"
#include "formats/ply.h"
#include "scene/sampler.h"

namespace raycast {
namespace {

using enum setting_id;
using vt = value_type;

// Text the table's rows point at, kept for the program's life.
std::string_view keep(std::string s) {
  static std::vector<std::unique_ptr<std::string>> kept;
  kept.push_back(std::make_unique<std::string>(std::move(s)));
  return *kept.back();
}

std::vector<std::string_view> backend_names() {
  std::vector<std::string_view> n{to_string(raycast::backend::automatic)};
  for (raycast::backend b : all_backends) n.push_back(to_string(b));
  return n;
}

std::vector<setting> build() {
  static const std::vector<std::string_view> backends = backend_names();
  static const std::vector<std::string_view> precisions = {to_string(raycast::precision::exact), to_string(raycast::precision::fast)};
  static const std::vector<std::string_view> samplers = {
      to_string(sampler_kind::random), to_string(sampler_kind::stratified), to_string(sampler_kind::sobol)};
  std::vector<setting> t(scene_settings().begin(), scene_settings().end());
  const auto run = [&](setting s) { t.push_back(s); };
  run({output, "--output", "-o", "", "", vt::text, {}, {}, "FILE", "",
       "Output file; '-' writes binary PPM to standard output"});
  run({scene, "--scene", "", "", "", vt::text, {}, {}, "NAME|FILE", "sky",
       keep("Built-in scene (" + builtin_scene_list() +
            ") or a .json scene file, whose settings the other options override, or a .ply particle file")});
  run({format, "--format", "", "", "format", vt::name, {}, io::format_name_list(), "FMT", "",
       "overrides the extension", 0, true});
  run({setting_id::backend, "--backend", "", "", "backend", vt::name, {}, backends, "NAME",
       "auto: the best this CPU runs", ""});
  run({setting_id::precision, "--precision", "", "", "precision", vt::name, {}, precisions, "MODE",
       to_string(default_precision), ""});
  run({threads, "--threads", "", "", "threads", vt::integer, {0, 1024}, {}, "N", "0: all cores", "Render threads"});
  run({samples, "--samples", "", "", "samples", vt::integer, {1, double(max_samples)}, {}, "N", "1",
       "Samples per pixel, averaged (antialiasing); 1 is the pixel's own point"});
  run({sampler, "--sampler", "", "", "sampler", vt::name, {}, samplers, "NAME", to_string(default_sampler),
       "where a pixel's samples fall"});
  run({seed, "--seed", "", "", "seed", vt::seed, {}, {}, "N", "0",
       "Seed of the samples' random numbers, 0 to 2^64-1"});
  run({region, "--region", "", "", "region", vt::region, {}, {}, "X0,Y0,X1,Y1", "the whole image",
       "Render and write only the pixels x0 <= x < x1, y0 <= y < y1 of the image (y0 = 0 is the top row), the "
       "same bytes as those of the whole image"});
  run({radius, "--radius", "", "", "radius", vt::real, {0.0, max_sphere_extent, true, false}, {}, "R",
       "the file's radius property", "Every sphere's radius, for a .ply particle file (instead of its radius property)"});
  run({color_by, "--color-by", "", "", "color_by", vt::text, {}, {}, "NAME", "the file's red green blue",
       "Colour a .ply particle file's spheres by this vertex property, through --colormap"});
  run({setting_id::colormap, "--colormap", "", "", "colormap", vt::name, {}, colormap_names, "NAME", "viridis",
       "The colours of --color-by, low to high"});
  run({color_range, "--color-range", "", "", "color_range", vt::interval, {}, {}, "LO,HI",
       "the property's min and max", "The values --color-by maps to the colormap's ends (beyond them: the ends)"});
  run({quiet, "--quiet", "-q", "", "", vt::flag, {}, {}, "", "", "No progress on standard error"});
  run({stats, "--stats", "", "", "", vt::flag, {}, {}, "", "",
       "After the run, print on standard error the seconds to load, prepare, render and write, rays per "
       "second, spheres and peak memory"});
  run({version, "--version", "", "", "", vt::flag, {}, {}, "", "", "Print the version and the backend auto picks here"});
  return t;
}

}  // namespace

particle_settings particles_of(const settings& s, std::string_view scene_name, bool keywords) {
  particle_settings r;
  for (setting_id id : {radius, color_by, setting_id::colormap, color_range}) {
    if (!s.has(id)) continue;
    r.refused = &input_row(id);
    if (!is_ply_file_name(scene_name)) {
      r.why = "applies to .ply particle files only (this scene gives its spheres' own radii and colours)";
      return r;
    }
    if ((id == setting_id::colormap || id == color_range) && !s.has(color_by)) {
      r.why = keywords ? "needs color_by (the property it colours by)" : "needs --color-by NAME (the property it colours by)";
      return r;
    }
    r.refused = nullptr;
  }
  if (s.has(radius)) r.options.radius = s[radius]->v.real;
  if (s.has(color_by)) r.options.color_by = s[color_by]->v.text;
  if (s.has(setting_id::colormap)) r.options.map = raycast::colormap(s[setting_id::colormap]->v.name);
  if (s.has(color_range)) r.options.color_range = {s[color_range]->v.triple[0], s[color_range]->v.triple[1]};
  return r;
}

std::span<const setting> input_table() {
  static const std::vector<setting> table = build();
  return table;
}

const setting& input_row(setting_id id) {
  for (const setting& row : input_table())
    if (row.id == id) return row;
  return input_table().front();
}

namespace {

// The row a camera, sky or light field is set by (the camera position has two).
setting_id row_for(scene_field f, const settings& s) {
  switch (f) {
    case scene_field::width: return width;
    case scene_field::height: return height;
    case scene_field::aspect: return aspect;
    case scene_field::viewport_height: return viewport_height;
    case scene_field::focal_length: return focal_length;
    case scene_field::origin: return s.has(origin) ? origin : lookfrom;
    case scene_field::lookat: return lookat;
    case scene_field::vup: return vup;
    case scene_field::vfov: return vfov;
    case scene_field::sky_bottom: return sky_bottom;
    case scene_field::sky_top: return sky_top;
    case scene_field::light_direction: return light;
    case scene_field::light_shadows: return shadows;
    case scene_field::ao_samples: return ao;
    case scene_field::ao_distance: return ao_distance;
    default: return setting_id::scene;
  }
}

}  // namespace

blamed blame(const invalid_field& e, const settings& merged, bool have_file) {
  const setting_id id = row_for(e.field, merged);
  // A file's values carry their place in it; other sources' do not.
  const bool from_file = have_file && (id == setting_id::scene || !merged.has(id) || !merged[id]->where.empty());
  return {id, from_file};
}

}  // namespace raycast
