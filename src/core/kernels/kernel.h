// The interface between the renderer and the per-ISA sky kernels.
#pragma once
#include <cstdint>

#include "float_scene.h"
#include "image.h"
#include "scalar.h"

namespace raycast::kernels {

// Everything a kernel reads, prepared once per render by the renderer.
struct kernel_args {
  const float_scene* scene = nullptr;
  precision prec = precision::exact;
  // Per column i, the part of the direction that depends on su only:
  // col[k][i] = centre[k] + su_i * horizontal[k] (scalar.h's inner bracket).
  // Padded with zeros to a multiple of 16 columns.
  const float* col[3] = {};
  // Lesson camera (scene->axis_aligned, and specializing): direction y and z
  // per row, col_x2[i] = col[0][i]^2 per column, so a batch needs one load.
  bool axis_aligned = false;
  const float* col_x2 = nullptr;
  // Lesson camera: mirrored columns (and, with `paired`, rows) share one |d|.
  bool mirror = false;
  // Channels whose two sky colours are equal never vary: computed once.
  bool constant[3] = {};
  float constant_value[3] = {};
  int32_t constant_byte[3] = {};
  // bottom + 1 * delta == top in float for every channel: the lerp reaches its
  // end points exactly, so scalar.h's select and clamp never change a value.
  bool lerp_exact = false;
  // Sky colours within [0, 1]: the 8-bit clamp to [0, 1] is a no-op and skipped.
  bool colours_in_unit_range = false;
};

// Fills rows [r0, r1) of the band; single-threaded. One per instruction set.
// With `paired` (lesson camera only; the band must hold both), each row r also
// fills its mirror row H-1-r, which shares every |d| (sky_kernel.inl).
using render_rows_fn = void (*)(const kernel_args& args, const image_band& band, int64_t r0,
                                int64_t r1, bool paired);

namespace sse2 { void render_rows(const kernel_args&, const image_band&, int64_t, int64_t, bool); }
namespace avx2 { void render_rows(const kernel_args&, const image_band&, int64_t, int64_t, bool); }
namespace avx512 { void render_rows(const kernel_args&, const image_band&, int64_t, int64_t, bool); }
namespace neon { void render_rows(const kernel_args&, const image_band&, int64_t, int64_t, bool); }

}  // namespace raycast::kernels
