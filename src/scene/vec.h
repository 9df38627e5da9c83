// The lesson's vector names on top of GLM: point3 and color are both dvec3.
#pragma once
#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace raycast {
using vec3 = glm::dvec3;
using point3 = glm::dvec3;  // a position in world space
using color = glm::dvec3;   // linear RGB
}  // namespace raycast
