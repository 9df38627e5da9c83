// Shading of the sphere kernel (sphere_kernel.inl), per instruction set:
// the sky where no sphere was hit, a hit's normal, headlight and colour
// (float_spheres.h), and the per-lane sums of the sampled path.
#pragma once
#include <cfloat>

#include "kernels/sampled_sky.h"
#include "kernels/sky_shade.inl"
#include "kernels/sphere_hit.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// The sky of the sphere kernel's misses (sky_shade.inl), with the sky
// kernel's shortcuts `channels` and `clamps` (render/plan.h), which the plan
// decides for sphere scenes too.
struct sky_shader {
  sky_colors colors;
  bool constant[3];
  bool lerp_exact;
  explicit sky_shader(const kernel_args& a) : colors(*a.scene), lerp_exact(a.lerp_exact) {
    for (int k = 0; k < 3; ++k) constant[k] = a.constant[k];
  }
  void shade(const rays& r, vfloat out[3]) const {
    const vfloat t = sky_t(exact_uy(r.d[1], r.n2));
    for (int k = 0; k < 3; ++k) {
      if (constant[k]) out[k] = colors.bottom[k];
      else if (lerp_exact) out[k] = colors.channel<true>(k, t);
      else out[k] = colors.channel<false>(k, t);
    }
  }
};

// The normal of each lane that hit a normal-shaded sphere (float_spheres.h):
// N, facing the ray inside a sphere.
template <int Shades>
RAYCAST_INLINE void hit_normal(const sphere_arrays& sp, const closest_hit<Shades>& h, const rays& r, vfloat n[3]) {
  const vfloat* d = r.d;
  const vfloat f[3] = {h.fx, h.fy, h.fz};
  for (int k = 0; k < 3; ++k) n[k] = (f[k] + h.s * d[k]) * h.inv_r;
  if (sp.any_inside) {  // face the ray, inside a sphere
    const vmask back = (h.inside == 1.0f) & ((n[0] * d[0] + n[1] * d[1]) + n[2] * d[2] >= 0.0f);
    for (int k = 0; k < 3; ++k) n[k] = select(back, -n[k], n[k]);
  }
}

// The headlight of lit spheres (float_spheres.h): lit_ambient + lit_diffuse
// max(-(N . d) / sqrt(n2), 0).
RAYCAST_INLINE vfloat headlight(const vfloat n[3], const vfloat d[3], vfloat n2) {
  const vfloat facing = -((n[0] * d[0] + n[1] * d[1]) + n[2] * d[2]) / sqrt(n2);
  return vfloat(lit_ambient) + vfloat(lit_diffuse) * max(facing, 0.0f);
}

// The hit colour of each lane that hit (float_spheres.h): 0.5 (N + 1), the
// sphere's flat colour, or its lit colour.
template <int Shades>
RAYCAST_INLINE void hit_color(const sphere_arrays& sp, const closest_hit<Shades>& h, const rays& r,
                               vfloat out[3]) {
  vfloat n[3];
  if constexpr ((Shades & normal_shading) != 0) {
    hit_normal(sp, h, r, n);
    for (int k = 0; k < 3; ++k) out[k] = (n[k] + 1.0f) * 0.5f;
  }
  const vfloat albedo[3] = {h.red, h.green, h.blue};
  if constexpr (Shades == flat_shading) {
    for (int k = 0; k < 3; ++k) out[k] = albedo[k];
  } else if constexpr (Shades == (normal_shading | flat_shading)) {
    const vmask flat = h.kind == shading_kind::flat;
    for (int k = 0; k < 3; ++k) out[k] = select(flat, albedo[k], out[k]);
  } else if constexpr (Shades == all_shadings) {
    const vmask flat = h.kind == shading_kind::flat, lit = h.kind == shading_kind::lit;
    const vfloat light = any(lit) ? headlight(n, r.d, r.n2) : vfloat(0.0f);
    for (int k = 0; k < 3; ++k) out[k] = select(flat, albedo[k], select(lit, albedo[k] * light, out[k]));
  }
}

// The colour of one batch (float_spheres.h): the closest hit's shading, the
// sky where nothing was hit.
template <int Shades>
RAYCAST_INLINE void shade(const sky_shader& sky, const sphere_arrays& sp, const closest_hit<Shades>& h,
                          const rays& r, vfloat out[3]) {
  if (none(h.hit)) {
    sky.shade(r, out);
    return;
  }
  vfloat hit[3];
  hit_color(sp, h, r, hit);
  if (all(h.hit)) {
    for (int k = 0; k < 3; ++k) out[k] = hit[k];
    return;
  }
  vfloat sky_color[3];
  sky.shade(r, sky_color);
  for (int k = 0; k < 3; ++k) out[k] = select(h.hit, hit[k], sky_color[k]);
}

// The per-lane sums of a sampled batch (kernels/scalar.h's order): flat and
// lit colours, normals and their count, the sky's u and count
// (kernels/sampled_sky.h). A lane adds only what its sample gave: + 0 leaves
// a sum that is never -0 unchanged, so the other lanes' adds change nothing.
struct sample_sums {
  vfloat flat[3] = {0.0f, 0.0f, 0.0f}, normals[3] = {0.0f, 0.0f, 0.0f}, normal_count = 0.0f;
  vfloat sky_sum = 0.0f, sky_count = 0.0f;

  // The sky in the lanes where this sample hit nothing; then in every lane.
  RAYCAST_INLINE void add_sky(const rays& r, vmask hit) {
    const vfloat sky = sampling::sky_u<vfloat, vuint>(r.d[1], r.n2);
    sky_sum = sky_sum + select(hit, 0.0f, sky);
    sky_count = sky_count + select(hit, vfloat(0.0f), vfloat(1.0f));
  }
  RAYCAST_INLINE void add_sky(const rays& r) {
    sky_sum = sky_sum + sampling::sky_u<vfloat, vuint>(r.d[1], r.n2);
    sky_count = sky_count + 1.0f;
  }

  // One sample's closest hits, then the sky where it hit nothing.
  template <int Shades>
  RAYCAST_INLINE void add(const sphere_arrays& sp, const closest_hit<Shades>& h, const rays& r) {
    if (any(h.hit)) {
      const bool every = all(h.hit);
      vfloat n[3];
      if constexpr ((Shades & normal_shading) != 0) {
        vmask normal = h.hit;
        if constexpr (mixed<Shades>) normal = normal & (h.kind == shading_kind::normal);
        hit_normal(sp, h, r, n);
        if constexpr (Shades == normal_shading) {
          for (int k = 0; k < 3; ++k) normals[k] = normals[k] + (every ? n[k] : select(normal, n[k], 0.0f));
        } else {
          for (int k = 0; k < 3; ++k) normals[k] = normals[k] + select(normal, n[k], 0.0f);
          normal_count = normal_count + select(normal, vfloat(1.0f), vfloat(0.0f));
        }
      }
      if constexpr ((Shades & flat_shading) != 0) {  // flat and lit colours
        vmask colored = h.hit;
        if constexpr (mixed<Shades>) colored = colored & !(h.kind == shading_kind::normal);
        vfloat c[3] = {h.red, h.green, h.blue};
        if constexpr (Shades == all_shadings) {
          const vmask lit = h.hit & (h.kind == shading_kind::lit);
          if (any(lit)) {
            const vfloat light = headlight(n, r.d, r.n2);
            for (int k = 0; k < 3; ++k) c[k] = select(lit, c[k] * light, c[k]);
          }
        }
        for (int k = 0; k < 3; ++k) flat[k] = flat[k] + select(colored, c[k], 0.0f);
      }
      if (every) return;
    }
    add_sky(r, h.hit);
  }

  // The pixels' colours from `count` samples (kernels/sampled_sky.h).
  template <int Shades>
  RAYCAST_INLINE void average(const float_scene& s, vfloat count, vfloat c[3]) {
    // A normal-shaded scene's normal count is what the sky did not take (exact: below 2^24).
    if constexpr (Shades == normal_shading) normal_count = count - sky_count;
    for (int k = 0; k < 3; ++k)
      c[k] = ((flat[k] + (normals[k] + normal_count) * 0.5f) + (sky_count * s.sky_mid[k] + sky_sum * s.sky_half[k])) / count;
  }
};

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
