#include "scene/scene.h"

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
  }
  return "?";
}

std::optional<invalid_field> validate(const scene_params& p) {
  if (auto e = validate(p.camera)) return e;
  return validate(p.sky);
}

scene make_scene(const scene_params& p) { return scene{make_camera(p.camera), p.sky}; }

}  // namespace raycast
