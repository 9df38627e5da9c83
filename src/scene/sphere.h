// The book's sphere (ch. 5-6): a centre, a radius and how its surface is
// shaded where a primary ray hits it (raycast/description.h's).
#pragma once
#include "raycast/description.h"

namespace raycast {

using api::shading;
using api::sphere;

// The headlight of `lit` spheres: a light at the camera, so a surface facing
// the viewer is at full colour and one seen edge-on at lit_ambient of it.
inline constexpr float lit_ambient = 0.2f;
inline constexpr float lit_diffuse = 0.8f;

}  // namespace raycast
