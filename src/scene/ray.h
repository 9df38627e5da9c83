// A ray P(t) = A + t*b: origin A, direction b (not necessarily unit length).
#pragma once
#include "scene/vec.h"

namespace raycast {

struct ray {
  point3 orig{0.0};
  vec3 dir{0.0};

  ray() = default;
  ray(const point3& origin, const vec3& direction) : orig(origin), dir(direction) {}

  point3 origin() const { return orig; }
  vec3 direction() const { return dir; }
  point3 at(double t) const { return orig + t * dir; }
};

}  // namespace raycast
