#include "render/plan.h"

#include <algorithm>
#include <new>

#include "prepare/float_scene.h"

namespace raycast {

plan::plan(const float_scene& f, precision p, unsigned allowed) {
  args_.scene = &f;
  args_.prec = p;
  args_.spheres = arrays_of(f.spheres);
  args_.spheres.axes = f.axes;
  // Per-column parts of the direction, in scalar.h's operations and order;
  // padded with zeros to whole 16-lane batches.
  const size_t padded = size_t(f.width + 15) / 16 * 16;
  const auto table = [padded] {
    float* t = static_cast<float*>(std::aligned_alloc(64, padded * sizeof(float)));
    if (!t) throw std::bad_alloc();
    std::fill(t, t + padded, 0.0f);
    return aligned_floats(t);
  };
  // The sphere kernel's `lanes` and `mirror` (kernel.h) need the three tables.
  const bool spheres = !f.spheres.empty();
  args_.lanes = (allowed & shortcut::lanes) && f.axis_aligned_camera;
  args_.mirror = args_.lanes && (allowed & shortcut::mirror);
  for (int k = 0; k < 3; ++k) {
    if (args_.lanes && !spheres && k > 0) break;  // the sky kernel reads x only
    column_part_[k] = table();
    for (int64_t i = 0; i < f.width; ++i)
      column_part_[k][size_t(i)] = f.center[k] + pixel_su(f, i) * f.horizontal[k];
    args_.column_part[k] = column_part_[k].get();
  }
  if (f.orthographic && spheres) {  // the rays' starts across the image plane, su plane_width per column
    ortho_x_ = table();
    for (int64_t i = 0; i < f.width; ++i) ortho_x_[size_t(i)] = pixel_su(f, i) * f.plane_width;
    args_.ortho_x = ortho_x_.get();
  }
  if (args_.lanes && !spheres) {
    column_x2_ = table();
    for (size_t i = 0; i < padded; ++i) column_x2_[i] = column_part_[0][i] * column_part_[0][i];
    args_.column_x2 = column_x2_.get();
  }
  bool unit = true, lerp_exact = true;
  for (int k = 0; k < 3; ++k) {
    args_.constant[k] = (allowed & shortcut::channels) && f.bottom[k] == f.top[k];
    args_.constant_value[k] = f.bottom[k];
    // The 8-bit value of a constant channel: scalar.h's clamp to [0, 1], then
    // the lesson's int(255.999 c).
    const float in_unit_range = f.bottom[k] > 0.0f ? (f.bottom[k] < 1.0f ? f.bottom[k] : 1.0f) : 0.0f;
    args_.constant_byte[k] = int32_t(in_unit_range * 255.999f);
    unit = unit && f.lo[k] >= 0.0f && f.hi[k] <= 1.0f;
    lerp_exact = lerp_exact && f.bottom[k] + 1.0f * f.delta[k] == f.top[k];
  }
  const bool clamps = allowed & shortcut::clamps;
  args_.lerp_exact = clamps && lerp_exact;
  args_.colors_in_unit_range = clamps && unit;
}

}  // namespace raycast
