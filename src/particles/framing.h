// The camera a particle file gets when no camera option is given, as OVITO
// frames a simulation: its cell (else its particles' bounds), widened by the
// largest radius, whole in the picture, seen from a corner or along an axis,
// through a perspective or an orthographic camera fitted the same way.
//   corner  from the (+x, +y, +z) corner towards -x -y -z, z up
//   x       from +x towards -x, z up;  y: from -y towards +y, z up;
//   z       from +z towards -z, y up
// Perspective: the nearest distance at which every corner lies inside the
// view (vertical field of view vfov, horizontal from the aspect), 2 % to
// spare. Orthographic: the image plane through lookfrom, in front of every
// particle, just high (and wide) enough for every corner, 2 % to spare.
#pragma once
#include <string_view>

#include "raycast/description.h"
#include "scene/particles.h"

namespace raycast {

// The field of view a framed perspective camera gets unless one is given.
inline constexpr double framing_vfov = 35.0;

struct framed_camera {
  api::vec3 lookfrom, lookat, vup;
  double vfov = framing_vfov;     // perspective
  double viewport_height = 0.0;   // orthographic
};

// view: "corner", "x", "y", "z" ("" is corner). r_max: the largest radius.
framed_camera frame_camera(const particle_frame& f, double r_max, std::string_view view, api::projection projection,
                           double vfov, double aspect);

}  // namespace raycast
