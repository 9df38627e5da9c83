// The sky the lesson's rays look at: a colour straight down and one straight up.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "scene/invalid.h"
#include "scene/vec.h"

namespace raycast {

// The sky a render looks at: api::sky's colours in GLM's vectors.
struct sky {
  color bottom{1.0, 1.0, 1.0};  // seen looking straight down (t = 0)
  color top{0.5, 0.7, 1.0};     // seen looking straight up (t = 1)
};
inline sky make_sky(const api::sky& s) { return {to_glm(s.bottom), to_glm(s.top)}; }

// Largest colour component magnitude accepted: far beyond any HDR sky, and
// small enough that top - bottom and every lerp stay finite in float.
inline constexpr double max_color = 1e30;

// Why the sky cannot be rendered, naming the colour, or nullopt.
inline std::optional<invalid_field> validate(const api::sky& s) {
  for (const auto& [field, c] : {std::pair{scene_field::sky_bottom, to_glm(s.bottom)}, {scene_field::sky_top, to_glm(s.top)}})
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(c[k]) <= max_color))
        return invalid_field{field, "colour components must be finite and within +-1e30"};
  return std::nullopt;
}

}  // namespace raycast
