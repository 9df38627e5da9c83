// raycast/raycast.h: scenes by name, from files and from text; errors.
#include "raycast/raycast.h"

#include "formats/registry.h"
#include "library/pipeline.h"
#include "library/source.h"
#include "scene/builtin.h"
#include "text/names.h"

namespace raycast::api {

error::error(enum kind k, std::string field, std::string message)
    : std::runtime_error(field.empty() ? message : field + ": " + message),
      kind_(k),
      field_(std::move(field)),
      message_(std::move(message)) {}

scene builtin_scene(const std::string& name) {
  auto spheres = builtin_spheres(name);
  if (!spheres)
    throw error(error::kind::invalid_argument, "scene",
                not_one_of(name, quote_token(name), raycast::builtin_scene_names()));
  scene s;
  s.spheres = std::move(*spheres);
  return s;
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> r;
  for (std::string_view n : raycast::builtin_scene_names()) r.emplace_back(n);
  return r;
}

namespace {

// The particle options as a settings layer: typed values, each checked by its row.
settings particle_layer(const particles& p) {
  if (auto e = check_particles(p)) throw library_error(refused(*e));
  settings s;
  const auto set = [&s](setting_id id) -> value& {
    given& g = s[id].emplace();
    g.source = input_row(id).keyword;
    return g.v;
  };
  if (p.radius) set(setting_id::radius).real = *p.radius;
  if (!p.color_by.empty()) set(setting_id::color_by).text = p.color_by;
  if (!p.colormap.empty()) {
    const setting& row = input_row(setting_id::colormap);
    parse_name(p.colormap, row.names, set(setting_id::colormap).name);
  }
  if (p.color_range) {
    value& v = set(setting_id::color_range);
    v.triple = {(*p.color_range)[0], (*p.color_range)[1], 0};
  }
  return s;
}

}  // namespace

scene load_scene(const std::string& path, const particles& p) try {
  if (!formats::names_a_file(path))
    throw refusal{error_kind::invalid_argument, "path", "",
                  quote_token(path) + " is not a .json scene file or a .ply particle file"};
  return describe(path, particle_layer(p), front_end::library).scene;
} catch (const refusal& r) {
  throw library_error(r);
}

scene parse_scene(const std::string& json_text) try {
  return describe_text(json_text, {}, front_end::library).scene;
} catch (const refusal& r) {
  throw library_error(r);
}

}  // namespace raycast::api
