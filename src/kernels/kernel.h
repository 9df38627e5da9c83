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

// Everything a kernel reads, prepared once per render by the plan
// (render/plan.h), which also decides which shortcuts this render takes.
struct kernel_args {
  const float_scene* scene = nullptr;
  precision prec = precision::exact;
  // Per column i, the part of the direction that depends on su only:
  // column_part[k][i] = centre[k] + su_i * horizontal[k] (scalar.h's inner
  // bracket; the rest, sv * vertical[k], is per row). Padded with zeros to a
  // multiple of 16 columns.
  const float* column_part[3] = {};
  // Shortcut `lanes` (the camera is axis-aligned): a batch carries no x or z
  // lanes; direction y and z are per row, column_x2[i] = column_part[0][i]^2.
  bool lanes = false;
  const float* column_x2 = nullptr;
  // For the sphere kernel, `lanes` means d.y and d.z per row (from the
  // tables' first column: the same bits in every column) and no x2 table.
  // Shortcut `mirror` (with `lanes`): mirrored columns (and, with `paired`,
  // rows) share one |d|. For the sphere kernel: the sky-only batches at both
  // ends of a row are shaded once for both ends.
  bool mirror = false;
  // Shortcut `channels`: channel k's two sky colours are equal, so it never
  // varies and is written as a constant.
  bool constant[3] = {};
  float constant_value[3] = {};
  int32_t constant_byte[3] = {};
  // Shortcut `clamps`, in two parts. bottom + 1 * delta == top in float for
  // every channel: the lerp reaches its end points exactly, so scalar.h's
  // select and clamp never change a value...
  bool lerp_exact = false;
  // ...and, for 8-bit output, sky colours within [0, 1]: the clamp to [0, 1]
  // before quantizing is a no-op.
  bool colors_in_unit_range = false;
  // An orthographic camera's ray starts across the image plane, per column:
  // ortho_x[i] = su_i * plane_width (float_scene.h); the row's is sv *
  // plane_height. Null for a perspective camera.
  const float* ortho_x = nullptr;
  // The sphere kernel's spheres (kernels/float_spheres.h); n = 0 for the sky.
  kernel_spheres spheres;
  // The frame's row index (kernels/culling.h; built by the renderer, with the
  // sampled path's spread when samples is set): row r's candidate spheres
  // are row_list[row_first[r] .. row_first[r + 1]), at most row_most, their
  // columns in units of 2^row_shift.
  const uint64_t* row_first = nullptr;
  const row_entry* row_list = nullptr;
  size_t row_most = 0;
  int row_shift = 0;
  // Many samples per pixel (scene/sampler.h): the sphere kernel's sampled
  // path, for every scene, the sky alone included; null for one sample.
  const sampling::sample_plan* samples = nullptr;
};

// The kernels of each target of simd/targets.h (namespace raycast::kernels::<target>;
// sky_kernel.cpp and sphere_kernel.cpp, compiled once per target):
//
// render_sky_rows: the sky kernel; fills rows [r0, r1) of the band (its
// column window: image_band); single-threaded. With `paired` (shortcut
// `mirror` only; the band must hold both), each row r also fills its mirror
// row H-1-r, which shares every |d|.
//
// render_sphere_rows: scenes with spheres, and every render of many samples
// per pixel; the same rows. The plan builds the three per-column direction
// tables and takes the shortcuts that apply to the sky (`channels`,
// `clamps`, `mirror`); both precisions give float_spheres.h's bits.
//
// trace_pixel: what the ray through pixel (i, j) hits (scalar.h's scalar_hit),
// every sphere of sp (arrays_of the scene's) tested in order; every target
// gives the same answer.
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
