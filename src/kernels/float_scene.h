// The scene as the float renderers see it, prepared once in double.
//
// The camera vectors are multiplied by one power of two so that the largest
// component lies in [0.5, 1). That is exact, leaves every unit direction
// bit-for-bit unchanged, and keeps squares of directions far from float
// overflow and underflow for viewports and focal lengths from 1e-38 to 1e38.
// The origin is not here: the sky depends on the direction only.
#pragma once
#include <cstdint>

#include "scene/scene.h"

namespace raycast {

struct float_scene {
  int64_t width = 0, height = 0;
  float last_col = 0, last_row = 0;  // W - 1 and H - 1
  float mid_col = 0, mid_row = 0;    // (W - 1) / 2 and (H - 1) / 2, exact in float
  float centre[3] = {};      // viewport centre - origin = -focal_length * w, scaled
  float horizontal[3] = {};  // scaled
  float vertical[3] = {};    // scaled
  float bottom[3] = {}, top[3] = {};
  float delta[3] = {};          // top - bottom, in float
  float lo[3] = {}, hi[3] = {};  // min and max of bottom and top
  // Fast mode's 8-bit shading folded into one multiply-add on y/|d|:
  // 255.999 * lerp(bottom, top, (uy + 1) / 2) = uy * fast_qa + fast_qb.
  float fast_qa[3] = {}, fast_qb[3] = {};
  // horizontal = (hx, 0, 0) and vertical = (0, vy, 0): the lesson's camera, so
  // a direction's y depends on the row only and z is constant (what the
  // `lanes` and `mirror` shortcuts use, render/plan.h).
  bool axis_aligned_camera = false;
};

float_scene prepare_float_scene(const scene& s);

}  // namespace raycast
