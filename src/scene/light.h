// How `lit` spheres are lit (api::light): the headlight (a light at the
// camera, the default), or a directional light with hard shadows; and
// ambient occlusion.
// Per channel, a lit sphere's colour is
//   colour (lit_ambient A + lit_diffuse max(0, N . L) S)      (scene/sphere.h)
// L the unit direction toward the light (the headlight's: -d / |d|, toward
// the camera), S 1 or the shadow ray's verdict (0 where any sphere lies
// between the hit and the light), A 1 or the fraction of `ao_samples`
// cosine-weighted directions about N along which nothing is hit within
// `ao_distance`. Normal- and flat-shaded spheres are not lit. The rays
// themselves: light/README.md.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "raycast/description.h"
#include "scene/invalid.h"
#include "scene/vec.h"

namespace raycast {

inline constexpr uint32_t max_ao_samples = 4096;

// Why the lighting cannot be rendered, naming the input, or nullopt.
inline std::optional<invalid_field> validate(const api::light& l) {
  if (l.direction) {
    const api::vec3& d = *l.direction;
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(d[k])) return invalid_field{scene_field::light_direction, "must be finite"};
    const double m = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
    if (m == 0.0) return invalid_field{scene_field::light_direction, "must not be 0,0,0 (it is a direction)"};
  }
  if (l.shadows && !l.direction)
    return invalid_field{scene_field::light_shadows,
                         "needs a directional light (--light X,Y,Z; the headlight casts no shadows)"};
  if (l.ao_samples > max_ao_samples)
    return invalid_field{scene_field::ao_samples, "is too large (at most " + std::to_string(max_ao_samples) + ")"};
  if (!(l.ao_distance > 0.0)) return invalid_field{scene_field::ao_distance, "must be above 0"};
  return std::nullopt;
}

}  // namespace raycast
