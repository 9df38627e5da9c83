// The sky the lesson's rays look at: a colour straight down and one straight up.
#pragma once
#include <cmath>
#include <optional>
#include <string>

#include "scene/vec.h"

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

}  // namespace raycast
