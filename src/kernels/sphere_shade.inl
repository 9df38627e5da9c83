// The sphere kernel's shading (float_spheres.h), and the sampled path's per-lane sums.
#pragma once
#include <cfloat>

#include "kernels/sampled_sky.h"
#include "light/secondary.h"
#include "kernels/sky_shade.inl"
#include "kernels/sphere_hit.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// The sky of the misses, with the shortcuts `channels` and `clamps`.
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

// The normal of each lane's hit, facing the ray inside a sphere; `back`: where it was turned.
template <int Shades>
RAYCAST_INLINE void hit_normal(const kernel_spheres& sp, const closest_hit<Shades>& h, const rays& r, vfloat n[3],
                               vmask* back = nullptr) {
  const vfloat* d = r.d;
  const vfloat f[3] = {h.fx, h.fy, h.fz};
  for (int k = 0; k < 3; ++k) n[k] = (f[k] + h.s * d[k]) * h.inv_r;
  if (sp.any_inside) {  // face the ray, inside a sphere
    const vmask turned = (h.inside == 1.0f) & ((n[0] * d[0] + n[1] * d[1]) + n[2] * d[2] >= 0.0f);
    for (int k = 0; k < 3; ++k) n[k] = select(turned, -n[k], n[k]);
    if (back) *back = turned;
  }
}

// A batch's pixels (lane l: column i0 + l of row j) and sample: ambient occlusion's numbers' key.
struct pixel_at {
  int64_t i0, j;
  uint32_t sample;
};

// The light of lit spheres (scene/light.h): lit_ambient + lit_diffuse max(N . L, 0), L the
// directional light's, or the headlight's: max(-(N . d) / sqrt(n2), 0). With shadow or ambient-
// occlusion rays, the lit lanes' light comes from light/secondary.h, compiled once.
template <int Shades>
RAYCAST_INLINE vfloat lit_light(const kernel_spheres& sp, const closest_hit<Shades>& h, const rays& r,
                                const vfloat n[3], vmask back, vmask lit, const pixel_at& at) {
  vfloat diffuse;
  if (sp.light) {
    diffuse = max((n[0] * sp.light[0] + n[1] * sp.light[1]) + n[2] * sp.light[2], 0.0f);
  } else {
    const vfloat* d = r.d;
    diffuse = max(-((n[0] * d[0] + n[1] * d[1]) + n[2] * d[2]) / sqrt(r.n2), 0.0f);
  }
  if (!sp.secondary) return vfloat(lit_ambient) + vfloat(lit_diffuse) * diffuse;
  alignas(64) float bits[2][N], light[lit_lanes::most > N ? lit_lanes::most : N] = {};
  lit_lanes ls;
  ls.i0 = at.i0, ls.j = at.j, ls.sample = at.sample;
  store(bits[0], select(lit, vfloat(1.0f), vfloat(0.0f)));
  store(bits[1], select(back, vfloat(1.0f), vfloat(0.0f)));
  store(light, as_float(h.index));
  for (int l = 0; l < N; ++l) __builtin_memcpy(&ls.sphere[l], &light[l], sizeof(float));
  for (int k = 0; k < 3; ++k) {
    store(light, n[k]);
    __builtin_memcpy(ls.n[k], light, sizeof(float) * N);
  }
  store(light, diffuse);
  __builtin_memcpy(ls.diffuse, light, sizeof(float) * N);
  for (int l = 0; l < N; ++l) {
    ls.lit |= bits[0][l] != 0.0f ? 1u << l : 0u;
    ls.inside |= bits[1][l] != 0.0f ? 1u << l : 0u;
  }
  light_lanes(*sp.secondary, ls, light);
  return vfloat::load(light);
}

// The hit colour of each lane that hit: 0.5 (N + 1), the flat colour, or the lit colour.
template <int Shades>
RAYCAST_INLINE void hit_color(const kernel_spheres& sp, const closest_hit<Shades>& h, const rays& r,
                               const pixel_at& at, vfloat out[3]) {
  vfloat n[3];
  vmask back{};
  if constexpr ((Shades & normal_shading) != 0) {
    hit_normal(sp, h, r, n, &back);
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
    const vfloat light = any(lit & h.hit) ? lit_light(sp, h, r, n, back, lit & h.hit, at) : vfloat(0.0f);
    for (int k = 0; k < 3; ++k) out[k] = select(flat, albedo[k], select(lit, albedo[k] * light, out[k]));
  }
}

template <int Shades>
RAYCAST_INLINE void shade(const sky_shader& sky, const kernel_spheres& sp, const closest_hit<Shades>& h,
                          const rays& r, const pixel_at& at, vfloat out[3]) {
  if (none(h.hit)) {
    sky.shade(r, out);
    return;
  }
  vfloat hit[3];
  hit_color(sp, h, r, at, hit);
  if (all(h.hit)) {
    for (int k = 0; k < 3; ++k) out[k] = hit[k];
    return;
  }
  vfloat sky_color[3];
  sky.shade(r, sky_color);
  for (int k = 0; k < 3; ++k) out[k] = select(h.hit, hit[k], sky_color[k]);
}

// The per-lane sums of a sampled batch (kernels/scalar.h's order). A lane adds only what its sample
// gave: + 0 leaves a sum that is never -0 unchanged.
struct sample_sums {
  vfloat flat[3] = {0.0f, 0.0f, 0.0f}, normals[3] = {0.0f, 0.0f, 0.0f}, normal_count = 0.0f;
  vfloat sky_sum = 0.0f, sky_count = 0.0f;

  // The sky where this sample hit nothing; then in every lane.
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
  RAYCAST_INLINE void add(const kernel_spheres& sp, const closest_hit<Shades>& h, const rays& r, const pixel_at& at) {
    if (any(h.hit)) {
      const bool every = all(h.hit);
      vfloat n[3];
      vmask back{};
      if constexpr ((Shades & normal_shading) != 0) {
        vmask normal = h.hit;
        if constexpr (mixed<Shades>) normal = normal & (h.kind == shading_kind::normal);
        hit_normal(sp, h, r, n, &back);
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
            const vfloat light = lit_light(sp, h, r, n, back, lit, at);
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
    // A normal-shaded scene's normal count is what the sky did not take (exact below 2^24).
    if constexpr (Shades == normal_shading) normal_count = count - sky_count;
    for (int k = 0; k < 3; ++k)
      c[k] = ((flat[k] + (normals[k] + normal_count) * 0.5f) + (sky_count * s.sky_mid[k] + sky_sum * s.sky_half[k])) / count;
  }
};

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
