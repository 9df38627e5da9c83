// The book's sphere (ch. 5-6): a centre, a radius and how its surface is
// shaded where a primary ray hits it.
#pragma once
#include <cstdint>

#include "scene/vec.h"

namespace raycast {

enum class shading : uint8_t {
  normal,  // 0.5 (N + 1) per channel, N the unit normal facing the ray (ch. 6)
  flat,    // one colour wherever it is hit (ch. 5's red sphere)
};

struct sphere {
  point3 center{0.0};
  double radius = 1.0;
  shading shade = shading::normal;
  color flat_color{1.0, 0.0, 0.0};  // read only when shade == flat
};

}  // namespace raycast
