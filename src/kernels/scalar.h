// The float renderer's contract: the reference's formulas in float, in one fixed order that every
// target (simd/targets.h) computes bit for bit in exact mode; the kernels (sky_kernel.cpp,
// sphere_kernel.cpp) are that order written once.
//
// For pixel column i, row j (j = 0 at the bottom), with the float_scene f:
//   su = W == 1 ? 0 : (float(i) - f.mid_col) / f.last_col   (= u - 1/2, in [-1/2, 1/2])
//   sv = H == 1 ? 0 : (float(j) - f.mid_row) / f.last_row   likewise for rows
//   d  = (f.centre + su * f.horizontal) + sv * f.vertical    per component
//   n2 = (d.x * d.x + d.y * d.y) + d.z * d.z
// From the viewport centre: the centre stays exact however small the focal length, and
// su(W-1-i) = -su(i), so the lesson camera's image is symmetric bit for bit (one |d| serves up to
// four pixels).
//
// exact (IEEE sqrt and divide):
//   uy = d.y / sqrt(max(n2, FLT_MIN))   (n2 below FLT_MIN only where d.y is 0: uy = 0, no 0/0)
//   t  = clamp((uy + 1) * 0.5, 0, 1)
//   c  = clamp(t == 1 ? top : bottom + t * delta, lo, hi)     per channel
//   8-bit: int(clamp(c, 0, 1) * 255.999f)
// fast (an estimate r and one Newton step, biased up by 2^-20 so straight up and down give +-1):
//   r  = rsqrt_estimate(max(n2, FLT_MIN))
//   uy = clamp((d.y * r) * (A - ((n2 * r) * r) * B), -1, 1),  A = 1.5 (1 + 2^-20), B = 0.5 (1 + 2^-20)
//   8-bit: int(clamp(uy * fast_qa + fast_qb, 0, 255.999));  float: t = (uy + 1) * 0.5, c as exact
// Fast mode's bits differ by backend (the estimate's precision, fused multiply-adds, regrouping);
// its error bound is in README.md and tests/support/error_bounds.h.
//
// Spheres: prepare/float_spheres.h gives their order, with d above; the exact sky where none is hit.
//
// Many samples per pixel (sampling/sampler.h): per pixel, base = (centre + su_i h) + sv_j v and
// step_x = (f.du unit) h, step_y = (f.dv unit) v (unit: the sampler's offset_unit, so the products
// are exact); sample s at offset counts (xi, eta) is the ray
//   d = (base + xi step_x) + eta step_y          per component
// hit as above. In sample order, per pixel: a normal-shaded hit adds its N (facing the ray) to
// `normals` and 1 to `normal count`; a flat or lit one its colour to `flat`; a miss adds to the sky
// sums (kernels/sampled_sky.h). Then, per channel,
//   pixel = ((flat + (normals + normal count) 0.5) + (sky count sky_mid + sky sum sky_half)) / float(N)
// Both precisions take this path.
//
// Every operation is one IEEE operation; the kernels are compiled with -ffp-contract=off.
#pragma once
#include <cstdint>

namespace raycast {

// What the float renderer's ray through a pixel hits (exact mode, every backend alike), to measure
// it against the double reference: the closest sphere's index (-1: none) and its distance from the
// camera origin in world units (kernel.h: trace_pixel).
struct scalar_hit {
  int64_t sphere = -1;
  double distance = 0.0;
};

}  // namespace raycast
