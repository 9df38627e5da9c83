// The scene as the float renderers see it, prepared once in double. The camera vectors are scaled
// by one power of two so that the largest component lies in [0.5, 1): exact, every unit direction
// unchanged, and squares of directions far from float overflow and underflow. The origin is in the
// spheres' constants (float_spheres.h); the sky reads the direction only.
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
  float du = 0, dv = 0;  // one pixel in su and sv: 1 / (W - 1), 1 / (H - 1); 0 for one column or row
  // How far a sample's ray may pass from its pixel's, over the distance (a pixel each way, +1 %).
  double pixel_spread = 0;
  float center[3] = {};      // viewport centre - origin = -focal_length * w, scaled
  float horizontal[3] = {};  // scaled
  float vertical[3] = {};    // scaled
  float bottom[3] = {}, top[3] = {};
  float delta[3] = {};          // top - bottom, in float
  float lo[3] = {}, hi[3] = {};  // min and max of bottom and top
  // The sky affine in u = d.y / |d|: bottom + (u + 1) / 2 delta = sky_mid + u sky_half (double).
  float sky_mid[3] = {}, sky_half[3] = {};
  // Fast mode's 8-bit shading: 255.999 lerp(bottom, top, (uy + 1) / 2) = uy fast_qa + fast_qb.
  float fast_qa[3] = {}, fast_qb[3] = {};
  // horizontal = (hx, 0, 0), vertical = (0, vy, 0): shortcuts `lanes` and `mirror` (render/plan.h).
  bool axis_aligned_camera = false;
  // Some |d|^2 may be below 2^-64 (|center| is): the sphere kernel guards batches (set_length).
  bool tiny_directions = false;
  // centre / its largest component: the centre ray's direction where centre is too short for float.
  float centre_unit[3] = {};
  // An orthographic camera: every ray has direction center (-w, scaled; horizontal and vertical
  // are 0) and starts on the image plane at lookfrom + px u + py v, px = su plane_width, py = sv
  // plane_height. The spheres' constants are in the camera's frame, depths measured from the plane
  // at depth plane_offset (float_spheres.h); `axes` turn a normal from that frame to the world's.
  bool orthographic = false;
  float plane_width = 0, plane_height = 0;
  float axes[3][3] = {};  // axes[a][k]: component k of u, v, d
  double plane_offset = 0;
  float_spheres spheres;  // empty for the sky alone
};

// su and sv of column i and row j (kernels/scalar.h), always inlined into the per-target kernels.
RAYCAST_INLINE float pixel_su(const float_scene& f, int64_t i) {
  return f.width == 1 ? 0.0f : (float(i) - f.mid_col) / f.last_col;
}
RAYCAST_INLINE float pixel_sv(const float_scene& f, int64_t j) {
  return f.height == 1 ? 0.0f : (float(j) - f.mid_row) / f.last_row;
}

// The order of the float scene's spheres. A scene of sort_from spheres or more is reordered by a
// stable counting sort that writes each record once, in its place (4 bytes a sphere for the keys,
// 4 a key a thread for the counts); smaller scenes keep the scene's order.
//  - rows: by the image row of their centres, so a row's spheres lie together in memory;
//  - depth: by the nearest distance |O - C| - r, in 2^16 buckets (float_spheres::depth_key), so a
//    batch's walk stops at what it sees (deep scenes: a ray passes many spheres behind its hit);
//  - automatic: depth where the spheres' screen discs add up to more than deep_from images, or
//    deep_from_small for fewer than small_scene spheres (whose records fit in the caches); else rows.
enum class sphere_order : uint8_t { automatic, scene, rows, depth };
inline constexpr double deep_from = 3.5, deep_from_small = 2.0;
inline constexpr size_t small_scene = size_t(1) << 18;

// With up to `threads` threads for large scenes; the same bytes for any count. Memory: 36 bytes a
// sphere (record, culling radius), 52 where flat or lit spheres look different, 4 more in depth order.
inline constexpr size_t sorted_from = size_t(1) << 15;
float_scene prepare_float_scene(const scene& s, int threads = 1, size_t sort_from = sorted_from,
                                sphere_order order = sphere_order::automatic);

}  // namespace raycast
