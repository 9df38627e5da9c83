// The float renderer's contract: the reference's formulas in float, in one
// fixed order that every target (simd/targets.h: the 1-lane scalar target
// and every SIMD one) computes bit for bit in exact mode. The kernels are
// that order written once (kernels/sky_kernel.cpp, sphere_kernel.cpp).
//
// For pixel column i, row j (j = 0 at the bottom), with the float_scene f:
//   su = W == 1 ? 0 : (float(i) - f.mid_col) / f.last_col   (= u - 1/2, in [-1/2, 1/2])
//   sv = H == 1 ? 0 : (float(j) - f.mid_row) / f.last_row   likewise for rows
//   d  = (f.centre + su * f.horizontal) + sv * f.vertical    per component
// Measuring from the viewport centre keeps the centre exact (no cancellation
// of corner + u * horizontal when the focal length is tiny next to the
// viewport) and makes mirrored pixels exact mirrors: su(W-1-i) = -su(i), so the
// lesson camera's image is symmetric bit for bit and the kernels compute each
// |d| once for up to four pixels.
//   n2 = (d.x * d.x + d.y * d.y) + d.z * d.z
//
// exact (IEEE sqrt and divide; every backend gives these bits):
//   uy = d.y / sqrt(max(n2, FLT_MIN))
//      (n2 below the smallest normal float happens only where d.y is 0, so
//      uy = 0 there: no 0/0, and denormal flushing cannot change a result)
//   t  = clamp((uy + 1) * 0.5, 0, 1)
//   c  = clamp(t == 1 ? top : bottom + t * delta, lo, hi)     per channel
//   8-bit: int(clamp(c, 0, 1) * 255.999f)
//
// fast (a hardware reciprocal-square-root estimate r and one Newton step,
// biased up by 2^-20 so that straight up and down land on exactly +-1):
//   r  = rsqrt_estimate(max(n2, FLT_MIN))
//   uy = (d.y * r) * (A - ((n2 * r) * r) * B),  A = 1.5 (1 + 2^-20), B = 0.5 (1 + 2^-20)
//        (fast_nr_a and fast_nr_b, kernels/newton.h)
//   uy = clamp(uy, -1, 1)
//   8-bit: int(clamp(uy * fast_qa + fast_qb, 0, 255.999))   (one multiply-add)
//   float: t = (uy + 1) * 0.5, then c as in exact mode
// The estimate differs between instruction sets (12 bits on SSE and AVX2, 14
// on AVX-512), AVX2/AVX-512 fuse the multiply-adds, and the kernels regroup
// (the lesson camera folds d.y into A and B and adds y^2 + z^2 first), so fast
// mode's bits differ by backend; its error bound is in src/kernels/README.md and tested
// (tests/support/error_bounds.h).
//
// Scenes with spheres: kernels/float_spheres.h gives their order (the
// direction d above, not normalized; the sky as in exact mode where no sphere is hit).
//
// Many samples per pixel (scene/sampler.h gives where they fall). Per
// pixel, its one-sample direction base = (centre + su_i h) + sv_j v (as
// above) and the steps step_x = (du unit) h, step_y = (dv unit) v (du, dv:
// f.du, f.dv; unit: the sampler's offset_unit, so du unit is exact); sample
// s, at offset counts (xi, eta), is the ray
//   d = (base + xi step_x) + eta step_y          per component
// (xi = eta = 0 is the one-sample ray), its hit as above. In sample order
// from 0, per pixel: a hit on a normal-shaded sphere adds its normal N (facing
// the ray inside a sphere) to `normals` and 1 to `normal count`; a hit on a
// flat or lit sphere adds its colour to `flat`; a sample that hits nothing adds to
// the sky sum instead (kernels/sampled_sky.h). Then, per channel,
//   pixel = ((flat + (normals + normal count) 0.5) + (sky count sky_mid + sky sum sky_half)) / float(N)
// -- the average of the samples' colours 0.5 (N + 1), flat colours and sky,
// with each affine map applied once per pixel rather than per sample.
// Both precisions: fast mode has no sampled path of its own.
//
// Every operation is a single IEEE operation; the kernels are compiled with
// -ffp-contract=off, so no fused multiply-add changes a rounding.
#pragma once
#include <cstdint>

namespace raycast {

// What the float renderer's ray through pixel (i, j) hits, for measuring its
// numerics against the double reference (the bench's stiff-sphere table and
// tests): sphere = the index of the closest sphere hit, -1 for none;
// distance = the float renderer's hit distance from the camera origin in
// world units, widened to double (0 when nothing is hit). Exact mode; every
// backend renders these hits bit for bit. scalar_trace (render/backend.h)
// is the 1-lane target's trace_pixel (kernels/kernel.h).
struct scalar_hit {
  int64_t sphere = -1;
  double distance = 0.0;
};

}  // namespace raycast
