#include "settings/resolve.h"

#include <algorithm>

namespace raycast {
namespace {

using enum setting_id;

api::vec3 vec(const value& v) { return {v.triple[0], v.triple[1], v.triple[2]}; }

// A setting that means nothing for an orthographic camera (its rays are
// parallel: no field of view, no focal length), refused naming both.
std::optional<setting_error> meaningless_for_orthographic(const settings& s) {
  for (setting_id id : {vfov, focal_length}) {
    if (!s.has(id)) continue;
    const given& g = *s[id];
    const std::string by = s.has(projection) ? s[projection]->source : "camera.projection";
    return setting_error{&input_row(id), g.source,
                         "means nothing with " + by +
                             " orthographic (its rays are parallel; the image plane is --viewport-height high)" +
                             g.where};
  }
  return std::nullopt;
}

std::optional<setting_error> checked(const settings& s, bool (*rows)(const setting&)) {
  for (const setting& row : input_table())
    if (rows(row) && s.has(row.id))
      if (auto e = check_range(row, s[row.id]->v, s[row.id]->tokens))
        return setting_error{&row, s[row.id]->source, *e + s[row.id]->where};
  return std::nullopt;
}

void apply_camera(const settings& s, api::camera& c) {
  const auto get = [&](setting_id id) -> const value* { return s.has(id) ? &s[id]->v : nullptr; };
  if (auto v = get(width)) c.width = v->integer;
  if (auto v = get(height)) c.height = v->integer;
  if (auto v = get(aspect)) c.aspect = v->real;
  if (auto v = get(viewport_height)) {
    c.viewport_height = v->real;
    c.vfov.reset();
  }
  if (auto v = get(vfov)) c.vfov = v->real;
  if (auto v = get(focal_length)) c.focal_length = v->real;
  if (auto v = get(projection)) c.projection = api::projection(v->name);
  if (auto v = get(origin)) c.lookfrom = vec(*v);
  if (auto v = get(lookfrom)) c.lookfrom = vec(*v);
  if (auto v = get(lookat)) c.lookat = vec(*v);
  if (auto v = get(vup)) {
    c.vup = vec(*v);
    // Derived after merging: the lesson's view from wherever the camera ended up.
    if (!c.lookat) c.lookat = api::vec3{c.lookfrom.x, c.lookfrom.y, c.lookfrom.z - 1.0};
  }
}

}  // namespace

std::optional<setting_error> resolve_scene(const settings& s, api::scene& d) {
  if (auto e = checked(s, is_scene_row)) return e;
  apply_camera(s, d.cam);
  if (d.cam.projection == api::projection::orthographic)
    if (auto e = meaningless_for_orthographic(s)) return e;
  const auto get = [&](setting_id id) -> const value* { return s.has(id) ? &s[id]->v : nullptr; };
  if (auto v = get(sky_bottom)) d.sky.bottom = vec(*v);
  if (auto v = get(sky_top)) d.sky.top = vec(*v);
  if (auto v = get(light)) d.light.direction = vec(*v);
  if (auto v = get(shadows)) d.light.shadows = v->flag;
  if (auto v = get(ao)) d.light.ao_samples = uint32_t(v->integer);
  if (auto v = get(ao_distance)) d.light.ao_distance = v->real;
  return std::nullopt;
}

std::optional<setting_error> resolve_particles(const settings& s, bool particle_file, api::particles& p,
                                               bool keywords) {
  if (auto e = checked(s, [](const setting& r) { return is_particle_row(r.id); })) return e;
  for (setting_id id : {type_radius, type_color, color_by, colormap, color_range, view}) {
    if (!s.has(id)) continue;
    const setting& row = input_row(id);
    if (!particle_file)
      return setting_error{&row, s[id]->source,
                           "applies to particle files only (this scene gives its spheres' own radii and colours)"};
    if ((id == colormap || id == color_range) && !s.has(color_by))
      return setting_error{&row, s[id]->source,
                           keywords ? "needs color_by (the column it colours by)"
                                    : "needs --color-by COLUMN (the column it colours by)"};
  }
  if (s.has(radius)) p.radius = s[radius]->v.real;
  for (const auto& [name, x] : s.has(type_radius) ? s[type_radius]->v.pairs : decltype(value::pairs){})
    p.type_radius.emplace_back(name, x[0]);
  for (const auto& [name, x] : s.has(type_color) ? s[type_color]->v.pairs : decltype(value::pairs){})
    p.type_color.emplace_back(name, api::vec3{x[0], x[1], x[2]});
  if (s.has(color_by)) p.color_by = s[color_by]->v.text;
  if (s.has(colormap)) p.colormap = input_row(colormap).names[s[colormap]->v.name];
  if (s.has(color_range)) {
    p.color_range = {s[color_range]->v.triple[0], s[color_range]->v.triple[1]};
    p.range_in_percentiles = s[color_range]->v.flag;
  }
  if (s.has(shade)) p.shade = api::shading(s[shade]->v.name);
  if (s.has(view)) p.view = input_row(view).names[s[view]->v.name];
  return std::nullopt;
}

std::optional<setting_error> resolve_run(const settings& s, run_settings& r) {
  if (auto e = checked(s, [](const setting& row) { return !is_scene_row(row) && !is_particle_row(row.id); }))
    return e;
  const auto name = [&](setting_id id) { return std::string(input_row(id).names[s[id]->v.name]); };
  api::options& o = r.options;
  if (s.has(backend)) o.backend = name(backend);
  if (s.has(precision)) o.precision = name(precision);
  if (s.has(threads)) o.threads = int(s[threads]->v.integer);
  if (s.has(samples)) o.samples = s[samples]->v.integer;
  if (s.has(sampler)) o.sampler = name(sampler);
  if (s.has(seed)) o.seed = s[seed]->v.seed;
  if (s.has(region)) {
    const auto& g = s[region]->v.region;
    o.region = api::region{g[0], g[1], g[2], g[3]};
  }
  if (s.has(format)) o.format = name(format);
  if (s.has(output)) r.output = s[output]->v.text;
  if (s.has(scene)) r.scene = s[scene]->v.text;
  r.quiet = s.has(quiet);
  r.stats = s.has(stats);
  return std::nullopt;
}

namespace {

// A name the row accepts, or why not, blaming the keyword.
std::optional<setting_error> checked_name(setting_id id, const std::string& text) {
  const setting& row = input_row(id);
  size_t k = 0;
  if (auto e = parse_name(text, row.names, k, row.any_case)) return setting_error{&row, std::string(row.keyword), *e};
  return std::nullopt;
}

std::optional<setting_error> checked_number(setting_id id, double x) {
  const setting& row = input_row(id);
  value v;
  v.integer = int64_t(x);
  v.real = x;
  const std::array<std::string, 3> tokens{number_text(x)};
  if (auto e = check_range(row, v, tokens)) return setting_error{&row, std::string(row.keyword), *e};
  return std::nullopt;
}

}  // namespace

std::optional<setting_error> check_options(const api::options& o) {
  if (auto e = checked_name(backend, o.backend)) return e;
  if (auto e = checked_name(precision, o.precision)) return e;
  if (auto e = checked_number(threads, o.threads)) return e;
  if (auto e = checked_number(samples, double(o.samples))) return e;
  if (auto e = checked_name(sampler, o.sampler)) return e;
  if (!o.format.empty())
    if (auto e = checked_name(format, o.format)) return e;
  return std::nullopt;
}

std::optional<setting_error> check_particles(const api::particles& p) {
  if (p.radius)
    if (auto e = checked_number(radius, *p.radius)) return e;
  if (!p.colormap.empty())
    if (auto e = checked_name(colormap, p.colormap)) return e;
  if (p.color_range && !((*p.color_range)[0] < (*p.color_range)[1]))
    return setting_error{&input_row(color_range), "color_range",
                         quote_token(number_text((*p.color_range)[0])) + " is not below " +
                             quote_token(number_text((*p.color_range)[1])) + " (want lo,hi with lo < hi)"};
  if (p.color_by.empty())
    for (setting_id id : {colormap, color_range})
      if (id == colormap ? !p.colormap.empty() : p.color_range.has_value())
        return setting_error{&input_row(id), std::string(input_row(id).keyword),
                             "needs color_by (the property it colours by)"};
  return std::nullopt;
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
    default: return scene;
  }
}

}  // namespace

blamed blame(const invalid_field& e, const settings& merged, bool have_file) {
  const setting_id id = row_for(e.field, merged);
  // A file's values carry their place in it; other sources' do not.
  const bool from_file = have_file && (id == scene || !merged.has(id) || !merged[id]->where.empty());
  return {id, from_file};
}

}  // namespace raycast
