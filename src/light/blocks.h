// The ball test of light/lanes.h (lanes::blocks) for one sphere and one ray,
// in the same float operations in the same order: the same verdict as any
// lane of any width gives it. For a hit seen from inside its own sphere and
// the light-space bins' candidates (light/far/shadow_bins.h).
#pragma once

namespace raycast {

// Whether the segment o + t d, t in [0, tmax], meets the solid ball s (x y z
// r): a start inside it, or the near root of a ball ahead within tmax
// (compared squared).
inline bool blocks_one(const float o[3], const float d[3], const float* s, float tmax) {
  const float ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const float r2 = s[3] * s[3];
  if ((ox * ox + oy * oy) + oz * oz <= r2) return true;
  const float b = (ox * d[0] + oy * d[1]) + oz * d[2];
  if (!(b < 0.0f)) return false;
  const float vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const float m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2, beyond = -b - tmax;
  return m2 <= r2 && (beyond <= 0.0f || beyond * beyond <= gap);
}

}  // namespace raycast
