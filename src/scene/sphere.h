// The book's sphere (ch. 5-6): a centre, a radius and how its surface is
// shaded where a primary ray hits it.
#pragma once
#include <cstdint>

#include "scene/vec.h"

namespace raycast {

enum class shading : uint8_t {
  normal,  // 0.5 (N + 1) per channel, N the unit normal facing the ray (ch. 6)
  flat,    // one colour wherever it is hit (ch. 5's red sphere)
  lit,     // its colour under a headlight: colour (lit_ambient + lit_diffuse max(0, N . -d/|d|))
};

// The headlight of `lit` spheres: a light at the camera, so a surface facing
// the viewer is at full colour and one seen edge-on at lit_ambient of it.
inline constexpr float lit_ambient = 0.2f;
inline constexpr float lit_diffuse = 0.8f;

struct sphere {
  point3 center{0.0};
  double radius = 1.0;
  shading shade = shading::normal;
  color flat_color{1.0, 0.0, 0.0};  // the colour of flat and lit spheres (unused for normal)
};

}  // namespace raycast
