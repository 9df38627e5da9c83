// The scene as the float renderers see it, prepared once in double.
//
// The camera vectors are multiplied by one power of two so that the largest
// component lies in [0.5, 1). That is exact, leaves every unit direction
// bit-for-bit unchanged, and keeps squares of directions far from float
// overflow and underflow for viewports and focal lengths from 1e-38 to 1e38.
// The origin is not here: the sky depends on the direction only; the spheres
// carry it in their per-sphere constants (kernels/float_spheres.h).
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/float_spheres.h"
#include "scene/scene.h"

namespace raycast {

struct float_scene {
  int64_t width = 0, height = 0;
  float last_col = 0, last_row = 0;  // W - 1 and H - 1
  float mid_col = 0, mid_row = 0;    // (W - 1) / 2 and (H - 1) / 2, exact in float
  // One pixel in su and sv: 1 / (W - 1) and 1 / (H - 1) in float, 0 for a
  // single column or row (a sample's offset, scene/sampler.h).
  float du = 0, dv = 0;
  // How far (as a fraction of the distance) a sample's ray may pass from the
  // pixel's one-sample ray: one pixel across in each direction over the
  // viewport's distance, and 1 % more. Culling widens each radius by it.
  double pixel_spread = 0;
  float centre[3] = {};      // viewport centre - origin = -focal_length * w, scaled
  float horizontal[3] = {};  // scaled
  float vertical[3] = {};    // scaled
  float bottom[3] = {}, top[3] = {};
  float delta[3] = {};          // top - bottom, in float
  float lo[3] = {}, hi[3] = {};  // min and max of bottom and top
  // The sky as an affine function of u = d.y / |d|: bottom + (u + 1) / 2 *
  // delta = sky_mid + u * sky_half (from bottom and delta in double; the
  // sampled path, kernels/sampled_sky.h).
  float sky_mid[3] = {}, sky_half[3] = {};
  // Fast mode's 8-bit shading folded into one multiply-add on y/|d|:
  // 255.999 * lerp(bottom, top, (uy + 1) / 2) = uy * fast_qa + fast_qb.
  float fast_qa[3] = {}, fast_qb[3] = {};
  // horizontal = (hx, 0, 0) and vertical = (0, vy, 0): the lesson's camera, so
  // a direction's y depends on the row only and z is constant (what the
  // `lanes` and `mirror` shortcuts use, render/plan.h).
  bool axis_aligned_camera = false;
  // The scene's spheres; empty for the sky alone (today's sky paths).
  float_spheres spheres;
};

float_scene prepare_float_scene(const scene& s);

// A sphere some ray of a row may hit, and the batches of `batch` columns
// (batch lo .. hi, inclusive: columns lo * batch .. hi * batch + batch - 1)
// whose rays may hit it.
struct sphere_span {
  uint32_t sphere;
  int32_t lo, hi;
};

// The spheres a ray of the row with this sv (kernels/scalar.h) may hit, in
// scene order, with their batches. Every ray of a row lies in the plane
// through the camera origin spanned by centre + sv * vertical and horizontal,
// so a sphere whose centre is farther than its radius from that plane is hit
// by none of them; of the others, a column's ray can hit the sphere only if
// its line comes within the radius of the centre, a quadratic in the column.
// The tests are in double on the float renderers' own constants, with a
// margin (1e-4 of |f| + r) hundreds of times the float intersection's
// rounding, so leaving a sphere out never changes a pixel. Writes to out
// (room for every sphere) and returns how many. (Raw memory: the kernels,
// compiled per instruction set, instantiate no standard-library templates.)
// With candidates, only those spheres (scene order) are considered: the
// others are known not to come near this row (sphere_rows).
// With spread (a float_scene's pixel_spread, for renders with many samples),
// the spheres a ray of the pixels' whole square of samples may hit: each
// radius widened by spread |f| (a ray within angle spread of another passes
// within spread |f| of where that one does, up to the sphere's distance).
size_t spheres_in_row(const float_scene& f, float sv, int batch, sphere_span* out,
                      const uint32_t* candidates = nullptr, size_t n_candidates = 0,
                      double spread = 0.0);

// The rows j (j = 0 at the bottom, kernels/scalar.h) whose plane may come
// near sphere k -- every row where spheres_in_row's plane test could keep
// it, and a little more; false when none does. So each row need not look at
// every sphere of the scene.
bool sphere_rows(const float_scene& f, uint32_t k, int64_t& j_lo, int64_t& j_hi, double spread = 0.0);

}  // namespace raycast
