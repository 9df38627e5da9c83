// The lesson's ray_color: a sky lerped on the y of the unit direction.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "ray.h"

namespace raycast {

struct sky {
  color bottom{1.0, 1.0, 1.0};  // seen looking straight down (t = 0)
  color top{0.5, 0.7, 1.0};     // seen looking straight up (t = 1)
};

// Largest colour component magnitude accepted: far beyond any HDR sky, and
// small enough that top - bottom and every lerp stay finite in float.
inline constexpr double max_colour = 1e30;

// Returns why the sky cannot be rendered, or nullopt.
inline std::optional<std::string> validate(const sky& s) {
  for (const color& c : {s.bottom, s.top})
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(c[k]) <= max_colour)) return "colour components must be finite and within +-1e30";
  return std::nullopt;
}

// b / |b|, scaled by its largest component first (as Eigen's stableNormalized)
// so that no square overflows or underflows; the zero vector stays zero.
inline vec3 unit_vector(const vec3& v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (m == 0.0) return vec3(0.0);
  const vec3 s = v / m;
  return s / std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
}

// t = 0.5 (unit.y + 1); colour = (1 - t) bottom + t top, kept inside the closed
// range between the two sky colours (rounding of the lerp cannot overshoot).
inline color ray_color(const ray& r, const sky& s) {
  const vec3 unit = unit_vector(r.direction());
  const double t = 0.5 * (unit.y + 1.0);
  const color c = (1.0 - t) * s.bottom + t * s.top;
  return glm::clamp(c, glm::min(s.bottom, s.top), glm::max(s.bottom, s.top));
}

// The lesson's int(255.999 c), with c clamped into [0, 1] first so that 1.0
// gives 255 and nothing wraps.
inline uint8_t to_byte(double c) {
  return static_cast<uint8_t>(255.999 * std::clamp(c, 0.0, 1.0));
}

}  // namespace raycast
