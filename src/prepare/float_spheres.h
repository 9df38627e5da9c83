// The spheres as the float renderers see them, and the order in which every
// float renderer (kernels/scalar.cpp, kernels/sphere_kernel.inl) intersects
// and shades them. Exact mode is this order on every backend, bit for bit.
//
// All primary rays start at the camera origin O, so everything that depends on
// O and a sphere only is a per-sphere constant, computed once in double and
// rounded to float once (prepare_float_scene). Each sphere first gets its own
// power of two 2^e with max(|f|, r) 2^-e in [0.5, 1), f = O - C (exact, and
// it changes no result but overflow and underflow: a sphere of radius 1e-30 or
// 1e30, or one 1e30 away, is as accurate as one of radius 1 next door). Per
// sphere, in that scaled unit:
//   f = (O - C) 2^-e,  c = |f|^2 - r^2 (double),  r2 = r^2,  inv_r = 1 / r,
//   scale = 2^e,  near = |f|^2 < 2 r^2  (the camera inside, or less than
//   0.42 r from the surface),  inside = c <= 0 (in double: the camera inside
//   the sphere or on its surface)
//
// Per pixel, the camera direction d of kernels/scalar.h (not normalized: the
// plan scales the camera so its largest component is in [0.5, 1)), and
//   n2 = (d.x d.x + d.y d.y) + d.z d.z,   inv_n2 = 1 / n2
// A ray is P(s) = O + s d; per sphere, in the float scene's order (the
// scene's; from 2^15 spheres on, stably sorted by the image row of their
// centres: prepare_float_scene), with closest = FLT_MAX:
//   b    = (f.x d.x + f.y d.y) + f.z d.z
//   near:   disc = b b - n2 c                          the textbook discriminant
//   far:    k = b inv_n2
//           v = (f.x - k d.x, f.y - k d.y, f.z - k d.z)  the chord's midpoint - C
//           disc = n2 (r2 - ((v.x v.x + v.y v.y) + v.z v.z))     Hearn & Baker
//   q    = -(b + copysign(sqrt(max(disc, 0)), b))      Press et al.: no cancellation
//   s0   = c / q,  s1 = q / n2                         the two roots, s0 s1 = c / n2
//   s    = s0 >= 0 ? s0 : s1                           the nearest root not behind,
//          for a sphere that holds the camera (inside); else s = s0 (c > 0:
//          both roots have q's sign, so a negative s0 is a sphere behind)
//   t    = s scale                                     exact: a power of two
//   hit  when disc >= 0 and s >= 0 and t <= closest (in a depth-ordered
//        scene: t < closest, or t == closest and the sphere comes later in
//        the scene than the closest hit's); then closest = t -- the book's
//        hittable_list: of two hits at the same t the later sphere wins (in
//        row order: of two coincident spheres; closest starts at FLT_MAX, so
//        no infinite or NaN t hits)
// Shading of the closest hit (its s, f, inv_r), per channel k:
//   flat:   the sphere's colour
//   lit:    with N as for normal (below), facing the ray,
//           light = lit_ambient + lit_diffuse max(-((N_0 d_0 + N_1 d_1) + N_2 d_2) / sqrt(n2), 0)
//           colour_k = colour_k light          (scene/sphere.h: 0.2 and 0.8)
//   normal: n_k = (f_k + s d_k) inv_r                    the outward normal
//           n = -n where inside and (n_0 d_0 + n_1 d_1) + n_2 d_2 >= 0
//                the book's set_face_normal: the normal faces the ray. From
//                outside a sphere (c > 0) the outward normal always does, so
//                it is not tested there: at a grazing hit the float dot
//                product's sign is rounding, and flipping on it would paint
//                the far side's colour.
//           colour_k = (n_k + 1) 0.5
// Where nothing is hit: kernels/scalar.h's exact sky, uy = d.y / sqrt(max(n2,
// FLT_MIN)), bit for bit. 8-bit: int(clamp(colour, 0, 1) * 255.999f), as the sky.
//
// Why this form:
//  - far spheres: the textbook b^2 - c loses everything to cancellation for a
//    small sphere far away (Ray Tracing Gems ch. 7: a unit sphere 4100 units
//    away renders as a solid square); r^2 - |v|^2 has an error relative to
//    r^2, not to |f|^2.
//  - near spheres (the ground under the camera): r^2 - |v|^2 subtracts two
//    numbers of size r^2 where the answer is small; b^2 - n2 c does not,
//    because c = |f|^2 - r^2 (tiny next to r^2: the camera is close to the
//    surface) is computed in double once. This is where the shared origin
//    pays: a float renderer with per-ray origins (the book in float, Embree)
//    forms c in float and loses it.
//  - q never cancels, and s0 = c / q takes the near root from the product of
//    the roots rather than from -b - sqrt(disc), which cancels when the camera
//    is near the surface.
//  - d is not normalized: no square root and no division per pixel but
//    inv_n2; t = s |d| is never formed, since every sphere compares the same s.
//
// An orthographic camera (float_scene.h) has no shared origin: per sphere,
// in its own power of two 2^e (of max(|cx|, |cy|, |cz|, r)), its centre in
// the camera's frame relative to lookfrom, cx, cy across the view and cz
// its depth less the plane offset z0, and c = 2^-e. Per ray from the plane
// point (px, py):
//   dx = px c - cx,  dy = py c - cy,  disc = r2 - (dx dx + dy dy)
//   s  = cz - sqrt(disc)   (the far root cz + sqrt(disc) where the plane cuts
//        the sphere, inside, and the near one is behind it);  t = s scale
// and the normal ((dx u + dy v) -+ sqrt(disc) d) inv_r in the world's axes.
//
// Precision `fast` renders spheres exactly as `exact` does (no estimate is
// used yet); only the sky-only scene has a separate fast path.
//
// Every operation is a single IEEE operation; the kernels are compiled with
// -ffp-contract=off, so no fused multiply-add changes a rounding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "memory/arrays.h"
#include "simd/inline.h"

namespace raycast {

struct secondary_rays;  // light/secondary.h

// A sphere's shading, as float_spheres::kind holds it.
namespace shading_kind {
inline constexpr float normal = 0.0f, flat = 1.0f, lit = 2.0f;
}

// What the intersection reads of one sphere, in one record of half a cache
// line: a ray batch tests spheres in the float scene's order, which jumps
// about memory, so each test costs one cache line rather than one per
// constant.
struct alignas(32) sphere_record {
  float fx, fy, fz;  // f = (O - C) 2^-e
  float c;           // |f|^2 - r^2, in double, in the scaled unit
  float r2;          // r^2 (scaled)
  float inv_r;       // 1 / r (scaled)
  float scale;       // 2^e
  uint8_t near;      // 1: the textbook discriminant; 0: Hearn & Baker
  uint8_t inside;    // 1: the camera is inside the sphere or on it
  uint16_t depth;    // a depth-ordered scene's bucket of |O - C| - r (float_spheres::depth_key)
};

// One record per sphere in the float scene's order, and what shading reads of a hit.
struct float_spheres {
  template <class T>
  using array = std::vector<T, page_allocator<T>>;  // memory/arrays.h
  array<sphere_record> rec;
  // Empty when every sphere is normal-shaded (!any_flat && !any_lit): the
  // colour (0 for normal-shaded spheres) and shading_kind of each sphere;
  // one entry for all where every sphere has the same shading and colour.
  array<float> red, green, blue;
  array<float> kind;
  bool any_flat = false, any_normal = false, any_lit = false, any_inside = false;
  // For culling (kernels/culling.h), in the sphere's unit: the radius
  // widened by a margin far above float's rounding, 1e-5 (|f| + r).
  array<float> cull_radius;
  // A depth-ordered scene's: each sphere's index in the scene, for the tie
  // rule (of two hits at the same t the later in the scene wins, whatever
  // the order they are tested in). Empty: ties go to the later in the float
  // scene's order, which is the scene's for a scene in its own order, and
  // keeps it among coincident spheres (the same key) in row order.
  out_of_order_array<uint32_t> order;  // written out of order (memory/pages.h)
  // A depth-ordered scene's (float_scene.h): the spheres sorted by their
  // nearest distance from the camera, |O - C| - r, in depth_buckets buckets;
  // depth_key[b] is at most every distance in bucket b times (1 - 2^-15), in
  // world units. A batch's walk over its spheres stops once every lane has
  // hit something nearer than the next sphere's key (kernels/sphere_hit.inl).
  static constexpr size_t depth_buckets = size_t(1) << 16;
  array<float> depth_key;

  size_t size() const { return rec.size(); }
  float kind_of(size_t k) const { return kind.empty() ? shading_kind::normal : kind[k & look_mask()]; }
  // Sphere k's entry in the colours is k & look_mask(): 0 where they hold one for all.
  size_t look_mask() const { return red.size() == 1 ? 0 : ~size_t(0); }
  bool empty() const { return rec.empty(); }
};

// The same arrays as plain pointers, for the kernels: they are compiled per
// instruction set and must instantiate no standard-library template (an
// inline function built for AVX-512 could be picked by the linker for the
// others). The plan (render/plan.cpp) fills it.
struct kernel_spheres {
  const sphere_record* rec = nullptr;
  const float *red = nullptr, *green = nullptr, *blue = nullptr, *kind = nullptr;
  const uint32_t* order = nullptr;  // null: the scene's order
  const float* depth_key = nullptr;  // null: not depth-ordered
  const float (*axes)[3] = nullptr;  // an orthographic camera's u, v, d (float_scene.h)
  size_t n = 0;
  bool any_flat = false, any_normal = false, any_lit = false, any_inside = false;
  // Whether each hit carries its sphere's index in the scene: for the tie
  // rule of a reordered scene, for trace_pixel and for secondary rays.
  bool track_index = false;
  // Lit spheres' light (scene/light.h): the unit direction toward a
  // directional light (3 floats), or null for the headlight; and the
  // shadow and ambient-occlusion rays, or null for none.
  const float* light = nullptr;
  const secondary_rays* secondary = nullptr;

  size_t look_mask = ~size_t(0);  // float_spheres::look_mask()

  // Sphere k's index in the scene.
  RAYCAST_INLINE uint32_t scene_index(size_t k) const { return order ? order[k] : uint32_t(k); }
  // Sphere k's entry in red, green, blue and kind.
  RAYCAST_INLINE size_t look(size_t k) const { return k & look_mask; }
};

inline kernel_spheres arrays_of(const float_spheres& s) {
  return {s.rec.data(), s.red.data(), s.green.data(), s.blue.data(), s.kind.data(),
          s.order.empty() ? nullptr : s.order.data(), s.depth_key.empty() ? nullptr : s.depth_key.data(), nullptr,
          s.size(), s.any_flat, s.any_normal, s.any_lit, s.any_inside, !s.order.empty(), nullptr, nullptr,
          s.look_mask()};
}

}  // namespace raycast
