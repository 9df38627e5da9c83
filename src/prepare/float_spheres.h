// The spheres as the float renderers see them, and the order in which every one (the sphere kernel
// at any width) intersects and shades them: exact mode is this order on every backend, bit for bit.
//
// Every primary ray starts at the camera origin O, so what depends on O and a sphere only is
// computed in double and rounded to float once, in the sphere's own unit 2^e with max(|f|, r) 2^-e
// in [0.5, 1), f = O - C (exact: a tiny, huge or far sphere is as accurate as a unit one nearby):
//   f = (O - C) 2^-e,  c = |f|^2 - r^2 (double),  r2 = r^2,  inv_r = 1 / r,  scale = 2^e,
//   near = |f|^2 < 2 r^2,  inside = c <= 0 (in double: the camera inside the sphere or on it)
// Per pixel, d is kernels/scalar.h's direction (not normalized) and
//   n2 = (d.x d.x + d.y d.y) + d.z d.z,   inv_n2 = 1 / n2
// A ray is P(s) = O + s d; per sphere, in the float scene's order (float_scene.h: sphere_order),
// with closest = FLT_MAX:
//   b    = (f.x d.x + f.y d.y) + f.z d.z
//   near:   disc = b b - n2 c                                      the textbook discriminant
//   far:    k = b inv_n2,  v = (f.x - k d.x, f.y - k d.y, f.z - k d.z)   the chord's midpoint - C
//           disc = n2 (r2 - ((v.x v.x + v.y v.y) + v.z v.z))          Hearn & Baker
//   q    = -(b + copysign(sqrt(max(disc, 0)), b))                  Press et al.: no cancellation
//   s0   = c / q,  s1 = q / n2                                     the two roots, s0 s1 = c / n2
//   s    = inside && !(s0 >= 0) ? s1 : s0    (outside, c > 0: both roots have q's sign, so a
//          negative s0 is a sphere behind)
//   t    = s scale                                                 exact: a power of two
//   hit  where disc >= 0, s >= 0 and t <= closest; then closest = t. Of two hits at the same t the
//        later sphere in the scene wins (the book's hittable_list; a depth-ordered scene compares
//        t < closest, or t == closest and a later scene index). No infinite or NaN t hits.
// Shading of the closest hit (its s, f, inv_r), per channel k:
//   flat:   the sphere's colour
//   lit:    colour_k (lit_ambient + lit_diffuse max(-((N_0 d_0 + N_1 d_1) + N_2 d_2) / sqrt(n2), 0)),
//           N as for normal (scene/sphere.h: 0.2 and 0.8)
//   normal: n_k = (f_k + s d_k) inv_r, the outward normal; n = -n where inside and
//           (n_0 d_0 + n_1 d_1) + n_2 d_2 >= 0 (set_face_normal; from outside the outward normal
//           always faces the ray, and a grazing hit's float sign is rounding: not tested there);
//           colour_k = (n_k + 1) 0.5
// Where nothing is hit: kernels/scalar.h's exact sky. 8-bit: int(clamp(colour, 0, 1) * 255.999f).
//
// Why: a far sphere's r^2 - |v|^2 errs relative to r^2, where b^2 - c cancels; a near one's
// b^2 - n2 c does not, as c is formed in double once (the shared origin's gain); s0 = c / q takes
// the near root without -b - sqrt(disc)'s cancellation; an unnormalized d costs no square root.
//
// An orthographic camera has no shared origin: per sphere, in its own 2^e (of max(|cx|, |cy|, |cz|,
// r)), its centre in the camera's frame relative to lookfrom (cx, cy across the view, cz its depth
// less the plane offset z0) and c = 2^-e. Per ray from the plane point (px, py):
//   dx = px c - cx,  dy = py c - cy,  disc = r2 - (dx dx + dy dy)
//   s  = cz - sqrt(disc)  (cz + sqrt(disc) where the plane cuts the sphere, inside, and the near
//        root is behind it);  t = s scale;  normal ((dx u + dy v) -+ sqrt(disc) d) inv_r
//
// Precision `fast` renders spheres as `exact` does. Every operation is one IEEE operation; the
// kernels are compiled with -ffp-contract=off.
#pragma once
#include <cstddef>
#include <cstdint>

#include "memory/arrays.h"
#include "simd/inline.h"

namespace raycast {

struct secondary_rays;  // light/secondary.h

// A sphere's shading, as float_spheres::kind holds it.
namespace shading_kind {
inline constexpr float normal = 0.0f, flat = 1.0f, lit = 2.0f;
}

// What the intersection reads of one sphere, in half a cache line: one miss a test.
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
  filled_array<sphere_record> rec;
  // Each sphere's colour (0 for normal-shaded) and shading_kind: empty when every sphere is
  // normal-shaded, one entry for all where every sphere has the same shading and colour.
  filled_array<float> red, green, blue, kind;
  bool any_flat = false, any_normal = false, any_lit = false, any_inside = false;
  // For culling (culling.h), in the sphere's unit: r + 1e-5 (|f| + r), far above float's rounding.
  filled_array<float> cull_radius;
  // A depth-ordered scene's index in the scene of each sphere, for the tie rule. Empty: ties go
  // to the later in the float scene's order, which keeps the scene's among coincident spheres.
  out_of_order_array<uint32_t> order;
  // A depth-ordered scene's buckets of the nearest distance |O - C| - r: depth_key[b] is at most
  // every distance in bucket b times (1 - 2^-15), in world units. A batch's walk stops once every
  // lane has hit something nearer than the next sphere's key (kernels/sphere_hit.inl).
  static constexpr size_t depth_buckets = size_t(1) << 16;
  filled_array<float> depth_key;

  size_t size() const { return rec.size(); }
  // Sphere k's entry in the colours is k & look_mask(): 0 where they hold one for all.
  size_t look_mask() const { return red.size() == 1 ? 0 : ~size_t(0); }
  bool empty() const { return rec.empty(); }
};

// The same arrays as plain pointers: the per-target kernels instantiate no standard-library template.
struct kernel_spheres {
  const sphere_record* rec = nullptr;
  const float *red = nullptr, *green = nullptr, *blue = nullptr, *kind = nullptr;
  const uint32_t* order = nullptr;  // null: the scene's order
  const float* depth_key = nullptr;  // null: not depth-ordered
  const float (*axes)[3] = nullptr;  // an orthographic camera's u, v, d (float_scene.h)
  size_t n = 0;
  bool any_flat = false, any_normal = false, any_lit = false, any_inside = false;
  bool track_index = false;  // hits carry the scene index: the tie rule, trace_pixel, secondary rays
  // Lit spheres' light (scene/light.h): the unit direction toward a directional light, or null
  // for the headlight; the shadow and ambient-occlusion rays, or null for none.
  const float* light = nullptr;
  const secondary_rays* secondary = nullptr;

  size_t look_mask = ~size_t(0);  // float_spheres::look_mask()

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
