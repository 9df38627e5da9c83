// The interface between the renderer and the per-ISA kernels (sky and spheres).
#pragma once
#include <cstdint>

#include "image/image.h"
#include "prepare/culling.h"
#include "prepare/float_scene.h"
#include "kernels/precision.h"
#include "kernels/scalar.h"
#include "sampling/sampler.h"
#include "simd/targets.h"

namespace raycast::kernels {

// Everything a kernel reads, prepared once per render by the plan (render/plan.h).
struct kernel_args {
  const float_scene* scene = nullptr;
  precision prec = precision::exact;
  // Per column i, column_part[k][i] = centre[k] + su_i * horizontal[k] (scalar.h's inner bracket;
  // sv * vertical[k] is per row), padded with zeros to a multiple of 16 columns.
  const float* column_part[3] = {};
  // Shortcut `lanes` (axis-aligned camera): d.y and d.z per row; column_x2[i] = column_part[0][i]^2.
  bool lanes = false;
  const float* column_x2 = nullptr;
  // Shortcut `mirror` (with `lanes`): mirrored columns (and, `paired`, rows) share one |d|.
  bool mirror = false;
  // Shortcut `channels`: channel k's two sky colours are equal, written as a constant.
  bool constant[3] = {};
  float constant_value[3] = {};
  int32_t constant_byte[3] = {};
  // Shortcut `clamps`: bottom + 1 * delta == top in every channel (scalar.h's select and clamp are
  // no-ops), and for 8-bit output sky colours in [0, 1] (so is the clamp before quantizing).
  bool lerp_exact = false;
  bool colors_in_unit_range = false;
  // Orthographic: the ray start per column, su_i * plane_width (the row's: sv plane_height).
  const float* ortho_x = nullptr;
  kernel_spheres spheres;  // n = 0 for the sky
  // The frame's row index (prepare/culling.h): row r's candidates are row_list[row_first[r] ..
  // row_first[r + 1]), at most row_most, their columns in units of 2^row_shift.
  const uint64_t* row_first = nullptr;
  const row_entry* row_list = nullptr;
  size_t row_most = 0;
  int row_shift = 0;
  // Many samples per pixel: the sphere kernel's sampled path, for every scene; null for one sample.
  const sampling::sample_plan* samples = nullptr;
};

// The kernels of each target of simd/targets.h (namespace raycast::kernels::<target>):
// - render_sky_rows fills rows [r0, r1) of the band (its column window); with `paired` (shortcut
//   `mirror`; the band must hold both) each row r also fills its mirror row H-1-r;
// - render_sphere_rows: scenes with spheres, and every render of many samples; the same rows, in
//   float_spheres.h's bits in both precisions;
// - trace_pixel: what the ray through pixel (i, j) hits, every sphere of sp tested in order.
using sky_rows_fn = void (*)(const kernel_args& args, const image_band& band, int64_t r0, int64_t r1,
                             bool paired);
using sphere_rows_fn = void (*)(const kernel_args& args, const image_band& band, int64_t r0, int64_t r1);
#define RAYCAST_DECLARE_KERNELS(name, arch, lanes, needs, flags)                            \
  namespace name {                                                                          \
  void render_sky_rows(const kernel_args&, const image_band&, int64_t, int64_t, bool);      \
  void render_sphere_rows(const kernel_args&, const image_band&, int64_t, int64_t);         \
  scalar_hit trace_pixel(const float_scene&, const kernel_spheres&, int64_t i, int64_t j);                         \
  }
RAYCAST_TARGETS(RAYCAST_DECLARE_KERNELS)
#undef RAYCAST_DECLARE_KERNELS

}  // namespace raycast::kernels
