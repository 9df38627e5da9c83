#include "scene/scene.h"

#include <cmath>
#include <string>
#include <utility>

namespace raycast {

std::string_view to_string(scene_field f) {
  switch (f) {
    case scene_field::width: return "camera.width";
    case scene_field::height: return "camera.height";
    case scene_field::aspect: return "camera.aspect";
    case scene_field::viewport_height: return "camera.viewport_height";
    case scene_field::focal_length: return "camera.focal_length";
    case scene_field::origin: return "camera.lookfrom";
    case scene_field::lookat: return "camera.lookat";
    case scene_field::vup: return "camera.vup";
    case scene_field::vfov: return "camera.vfov";
    case scene_field::sky_bottom: return "sky.bottom";
    case scene_field::sky_top: return "sky.top";
    case scene_field::sphere_center: return "spheres[].center";
    case scene_field::sphere_radius: return "spheres[].radius";
    case scene_field::sphere_color: return "spheres[].color";
    case scene_field::spheres: return "spheres";
    case scene_field::light_direction: return "light.direction";
    case scene_field::light_shadows: return "light.shadows";
    case scene_field::ao_samples: return "ambient_occlusion.samples";
    case scene_field::ao_distance: return "ambient_occlusion.distance";
  }
  return "?";
}

std::string path(const invalid_field& e) {
  switch (e.field) {
    case scene_field::sphere_center:
    case scene_field::sphere_radius:
    case scene_field::sphere_color: {
      const std::string_view s = to_string(e.field);  // "spheres[].name"
      return "spheres[" + std::to_string(e.index) + "]" + std::string(s.substr(s.find(']') + 1));
    }
    default: return std::string(to_string(e.field));
  }
}

std::optional<invalid_field> validate(const sphere& s, size_t index) {
  const auto bad = [index](scene_field f, std::string why) {
    return std::optional<invalid_field>(invalid_field{f, std::move(why), index});
  };
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(s.center[k])) return bad(scene_field::sphere_center, "sphere centre must be finite");
  if (!(std::isfinite(s.radius) && s.radius > 0.0))
    return bad(scene_field::sphere_radius, "sphere radius must be a positive finite number");
  if (s.radius > max_sphere_extent)
    return bad(scene_field::sphere_radius, "sphere radius must be at most 1e37 (the float renderers' range)");
  if (s.shade != shading::normal)
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(s.color[k]) <= max_color))
        return bad(scene_field::sphere_color, "colour components must be finite and within +-1e30");
  return std::nullopt;
}

std::vector<sphere> sphere_vector(const scene& s) {
  std::vector<sphere> v(s.sphere_count());
  for (size_t k = 0; k < v.size(); ++k) v[k] = s.sphere_at(k);
  return v;
}

std::optional<invalid_field> validate(const api::scene& p) {
  if (auto e = validate(p.cam)) return e;
  if (auto e = validate(p.sky)) return e;
  if (auto e = validate(p.light)) return e;
  const size_t n = p.arrays ? p.arrays->count : p.spheres.size();
  if (n > max_spheres)
    return invalid_field{scene_field::spheres,
                         "at most " + std::to_string(max_spheres) + " spheres (the renderers' 32-bit sphere indices), not " +
                             std::to_string(n),
                         0};
  for (size_t k = 0; k < n; ++k) {
    const sphere s = p.sphere_at(k);
    if (auto e = validate(s, k)) return e;
    // As a scene file's sphere: flat and lit take the colour they show.
    if (p.arrays && !p.arrays->colors.data && s.shade != shading::normal)
      return invalid_field{scene_field::sphere_color,
                           s.shade == shading::flat ? "is required for flat shading" : "is required for lit shading", k};
    for (int c = 0; c < 3; ++c)
      if (!(std::abs(p.cam.lookfrom[c] - s.center[c]) <= max_sphere_extent))
        return invalid_field{scene_field::sphere_center,
                             "sphere centre must be within 1e37 of the camera (lookfrom) in each coordinate "
                             "(the float renderers' range)",
                             k};
  }
  return std::nullopt;
}

scene make_scene(const api::scene& d) {
  return scene{make_camera(d.cam), make_sky(d.sky), d.spheres, d.arrays, d.light};
}

scene make_scene(api::scene&& d) {
  return scene{make_camera(d.cam), make_sky(d.sky), std::move(d.spheres), d.arrays, d.light};
}

}  // namespace raycast
