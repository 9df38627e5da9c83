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

#include "prepare/float_spheres.h"
#include "scene/scene.h"
#include "simd/inline.h"

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
  float center[3] = {};      // viewport centre - origin = -focal_length * w, scaled
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
  // Some ray's squared direction may be below 2^-64 (a degenerate camera:
  // every direction is at least as long as center, which is that short):
  // the sphere kernel then guards each batch (sphere_hit.inl, set_length).
  bool tiny_directions = false;
  // The viewport centre's direction alone, centre / its largest component:
  // the direction of a ray through the centre where centre itself is too
  // short to survive in float (a focal length below 2^-100 of the viewport).
  float centre_unit[3] = {};
  // An orthographic camera (scene/camera.h): every ray has the direction
  // center (the unit view direction -w, scaled; horizontal and vertical are
  // 0, so the sky reads one direction everywhere) and starts on the image
  // plane at lookfrom + px u + py v, px = su plane_width and py = sv
  // plane_height in world units (the kernels' per-column table and per-row
  // value). The spheres' constants are in the camera's frame, their depth
  // measured from the plane at depth plane_offset (float_spheres.h); `axes`
  // turn a normal from that frame (u, v, the view direction) to the world's.
  bool orthographic = false;
  float plane_width = 0, plane_height = 0;
  float axes[3][3] = {};  // axes[a][k]: component k of u, v, d
  double plane_offset = 0;
  // The scene's spheres; empty for the sky alone (today's sky paths).
  float_spheres spheres;
};

// su and sv of column i and row j (kernels/scalar.h): 0 for a single column
// or row. Always inlined: the per-target kernels call them, and no copy built
// with one target's flags may stand in for another's.
RAYCAST_INLINE float pixel_su(const float_scene& f, int64_t i) {
  return f.width == 1 ? 0.0f : (float(i) - f.mid_col) / f.last_col;
}
RAYCAST_INLINE float pixel_sv(const float_scene& f, int64_t j) {
  return f.height == 1 ? 0.0f : (float(j) - f.mid_row) / f.last_row;
}

// The order of the float scene's spheres. A scene of sort_from spheres or
// more is reordered by a stable counting sort that writes each record once,
// in its place; while it runs it holds 4 bytes a sphere (the keys) and 4
// bytes a key a thread (the counts). Scenes of a few thousand spheres fit in
// the caches as they come and keep the scene's order.
//  - rows: by the image row of their centres, so that the spheres one row of
//    rays tests lie together in memory (sparse and dense clouds: every sphere
//    is seen, and the walk over a row streams through memory);
//  - depth: by their nearest distance from the camera, |O - C| - r, in 2^16
//    buckets (float_spheres::depth_key), so that every batch's list is in
//    depth order and its walk stops at what it sees (deep scenes: a packed
//    box, where a ray passes dozens of spheres behind the one it hits).
//  - automatic: depth where the spheres' screen discs add up to more than
//    deep_from times the image (the scene is deep), or more than
//    deep_from_small times for a scene of fewer than small_scene spheres,
//    whose records (32 bytes each) fit in the caches, so that depth order's
//    scattered reads cost little; else rows. (Measured on the bench's
//    families: a dense cloud, 3 image areas, renders 25 % faster in depth
//    order at 10^5 spheres and 12 % slower at 10^6; a packed box 2.1 to 2.6
//    times faster from 3 10^4 spheres, 2.9 image areas, to 10^6, 9.5.)
enum class sphere_order : uint8_t { automatic, scene, rows, depth };
inline constexpr double deep_from = 3.5, deep_from_small = 2.0;
inline constexpr size_t small_scene = size_t(1) << 18;

// With up to `threads` threads for large scenes; the same bytes for any count.
// Memory: 36 bytes a sphere (float_spheres: a 32-byte record and the culling
// radius), 52 when flat or lit spheres differ in shading or colour (the
// colours and kinds; where every sphere looks the same, one of each), and 4
// more for a depth-ordered scene (each sphere's index in the scene).
inline constexpr size_t sorted_from = size_t(1) << 15;
float_scene prepare_float_scene(const scene& s, int threads = 1, size_t sort_from = sorted_from,
                                sphere_order order = sphere_order::automatic);

}  // namespace raycast
