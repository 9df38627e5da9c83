// Why a scene cannot be rendered, with the input to blame as data: the CLI
// maps the field to its option, a scene file to its key, nobody searches the
// message text.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace raycast {

// Every input of a scene a caller can get wrong. to_string gives its path as
// a scene file would spell it ("camera.vfov", "sky.top").
enum class scene_field : uint8_t {
  width,
  height,
  aspect,  // also blamed for a height derived from width / aspect
  viewport_height,
  focal_length,
  origin,  // the book's lookfrom
  lookat,
  vup,
  vfov,
  sky_bottom,
  sky_top,
  sphere_center,  // of spheres[invalid_field::index]
  sphere_radius,
  sphere_color,
  spheres,  // their count
  light_direction,
  light_shadows,
  ao_samples,
  ao_distance,
};

std::string_view to_string(scene_field f);

struct invalid_field {
  scene_field field;
  std::string message;  // a sentence naming the parameter and the rule it breaks
  size_t index = 0;     // which sphere, for the sphere_* fields
};

// The field's path as a scene file spells it, with the sphere's index:
// "camera.vfov", "spheres[3].radius".
std::string path(const invalid_field& e);

}  // namespace raycast
