// The float renderer: the reference's formulas in float, in one fixed order
// that every SIMD backend reproduces bit for bit in exact mode.
//
// For pixel column i, row j (j = 0 at the bottom), with the float_scene f:
//   u  = W == 1 ? 0.5 : float(i) / f.wm1        v likewise with j and f.hm1
//   d  = (f.corner + u * f.horizontal) + v * f.vertical      per component
//   n2 = (d.x * d.x + d.y * d.y) + d.z * d.z
//   uy = n2 >= FLT_MIN ? d.y / sqrt(n2) : 0                   (exact)
//      = n2 >= FLT_MIN ? d.y * rsqrt_nr(n2) : 0               (fast)
//   t  = clamp((uy + 1) * 0.5, 0, 1)
//   c  = clamp(t == 1 ? top : bottom + t * delta, lo, hi)     per channel
//   8-bit: int(clamp(c, 0, 1) * 255.999f)
// Every operation is a single IEEE operation; the file is compiled with
// -ffp-contract=off, so no fused multiply-add changes a rounding.
#pragma once
#include "float_scene.h"
#include "image.h"

namespace raycast {

enum class precision : uint8_t {
  exact,  // IEEE sqrt and divide
  fast,   // approximate reciprocal square root + one Newton step
};

// Colour of pixel (i, j) in the documented order; out receives r, g, b.
void scalar_pixel(const float_scene& f, precision p, int64_t i, int64_t j, float out[3]);

// Fills the band's rows; single-threaded.
void render_scalar(const float_scene& f, precision p, const image_band& band);

}  // namespace raycast
