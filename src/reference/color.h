// The lesson's ray_color and write_color in double: the oracle's shading and quantization.
#pragma once
#include <algorithm>
#include <cstdint>

#include "scene/camera.h"
#include "scene/sky.h"

namespace raycast {

// t = 0.5 (unit.y + 1); colour = (1 - t) bottom + t top, clamped between the two sky colours.
inline color ray_color(const ray& r, const sky& s) {
  const vec3 unit = unit_vector(r.direction());
  const double t = 0.5 * (unit.y + 1.0);
  const color c = (1.0 - t) * s.bottom + t * s.top;
  return glm::clamp(c, glm::min(s.bottom, s.top), glm::max(s.bottom, s.top));
}

// The lesson's int(255.999 c), c clamped to [0, 1] first.
inline uint8_t to_byte(double c) {
  return static_cast<uint8_t>(255.999 * std::clamp(c, 0.0, 1.0));
}

}  // namespace raycast
