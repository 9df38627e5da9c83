// An orthonormal frame (t, b) about a unit vector n, branchless (Duff et al.,
// "Building an orthonormal basis, revisited", JCGT 2017): the axes of the
// ambient-occlusion rays' hemisphere and of the light's view across L.
#pragma once
#include <cmath>

namespace raycast {

inline void frame_about(const float n[3], float t[3], float b[3]) {
  const float sign = std::copysign(1.0f, n[2]);
  const float a = -1.0f / (sign + n[2]);
  const float c = n[0] * n[1] * a;
  t[0] = 1.0f + sign * n[0] * n[0] * a;
  t[1] = sign * c;
  t[2] = -sign * n[0];
  b[0] = c;
  b[1] = sign + n[1] * n[1] * a;
  b[2] = -n[1];
}

}  // namespace raycast
