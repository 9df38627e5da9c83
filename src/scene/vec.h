// The lesson's vector names on top of GLM: point3 and color are both dvec3.
#pragma once
#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "raycast/description.h"

namespace raycast {
using vec3 = glm::dvec3;
using point3 = glm::dvec3;  // a position in world space
using color = glm::dvec3;   // linear RGB

// A description's vector as GLM's, for the arithmetic.
inline vec3 to_glm(const api::vec3& v) { return vec3(v.x, v.y, v.z); }

// b / |b|, scaled by its largest component first (as Eigen's stableNormalized)
// so that no square overflows or underflows; the zero vector stays zero.
inline vec3 unit_vector(const vec3& v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (m == 0.0) return vec3(0.0);
  const vec3 s = v / m;
  return s / std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
}

}  // namespace raycast
