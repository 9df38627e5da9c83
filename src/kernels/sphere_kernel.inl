// The sphere kernel, written once against the width-generic vector layer and
// compiled per instruction set (sphere_sse2.cpp, sphere_avx2.cpp,
// sphere_avx512.cpp each define RAYCAST_ISA and include their simd/ header
// first), as the sky kernel is.
//
// One batch is vfloat::size pixels of a row (8, or 16 with AVX-512). The rays
// are a structure of arrays in registers (unit direction x, y, z; the origin is
// shared by every primary ray and lives in the spheres' constants); the
// spheres are a structure of arrays in memory (kernels/float_spheres.h), each
// sphere's constants broadcast to every lane. Closest hit with masks: per
// lane, the nearest t so far and what shading needs of the sphere that gave it.
// Both precisions perform kernels/float_spheres.h's operations in its order,
// so the output is bit-identical to render_scalar.
//
// Left out where the scene does not need it: a sphere whose centre is farther
// than its radius from the plane of a row's rays is not tested on that row
// (spheres_near_row, kernels/float_scene.h); a sphere that no lane of the
// batch can hit (every disc < 0) costs no square root or division; a
// flat-shaded scene tracks no centres and computes no normals, a
// normal-shaded one tracks no colours; a batch where no lane hit anything
// computes no shading but the sky's.
#include <cfloat>
#include <cstdint>
#include <cstdlib>

#include "kernels/kernel.h"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;

// Which shadings the scene's spheres use (bit 0: normal, bit 1: flat).
constexpr int normal_shading = 1;
constexpr int flat_shading = 2;

// The closest hit per lane, and what shading reads of its sphere.
template <int Shades>
struct closest_hit {
  vmask hit{};                 // all false
  vfloat t = FLT_MAX;          // float_spheres.h: closest starts at FLT_MAX
  vfloat fx = 0.0f, fy = 0.0f, fz = 0.0f, inv_r = 0.0f;  // normal shading
  vfloat red = 0.0f, green = 0.0f, blue = 0.0f, flat = 0.0f;  // flat shading
};

// Tests the spheres near[0 .. count) (every sphere, 0 .. count, when near is null).
template <int Shades>
RAYCAST_INLINE void intersect(const sphere_arrays& sp, const uint32_t* near, size_t count, vfloat ux,
                              vfloat uy, vfloat uz, closest_hit<Shades>& h) {
  for (size_t x = 0; x < count; ++x) {
    const size_t k = near ? near[x] : x;
    const vfloat fx = sp.fx[k], fy = sp.fy[k], fz = sp.fz[k];
    const vfloat b = (fx * ux + fy * uy) + fz * uz;
    const vfloat vx = fx - b * ux, vy = fy - b * uy, vz = fz - b * uz;
    const vfloat disc = vfloat(sp.r2[k]) - ((vx * vx + vy * vy) + vz * vz);
    const vmask can_hit = disc >= 0.0f;
    if (none(can_hit)) continue;  // no lane can hit it: no sqrt, no divide
    const vfloat s = sqrt(max(disc, 0.0f));
    const vfloat q = -(b + copysign(s, b));
    const vfloat t0 = vfloat(sp.c[k]) / q;
    const vfloat t = select(t0 >= 0.0f, t0, q);
    const vmask m = can_hit & (t >= 0.0f) & (t <= h.t);
    h.t = select(m, t, h.t);
    h.hit = h.hit | m;
    if constexpr ((Shades & normal_shading) != 0) {
      h.fx = select(m, fx, h.fx);
      h.fy = select(m, fy, h.fy);
      h.fz = select(m, fz, h.fz);
      h.inv_r = select(m, vfloat(sp.inv_r[k]), h.inv_r);
    }
    if constexpr ((Shades & flat_shading) != 0) {
      h.red = select(m, vfloat(sp.red[k]), h.red);
      h.green = select(m, vfloat(sp.green[k]), h.green);
      h.blue = select(m, vfloat(sp.blue[k]), h.blue);
      if constexpr (Shades == (normal_shading | flat_shading))
        h.flat = select(m, vfloat(sp.flat[k]), h.flat);
    }
  }
}

// The sky's constants in registers, loaded once per call.
struct sky_shader {
  vfloat bottom[3], top[3], delta[3], lo[3], hi[3];
  explicit sky_shader(const float_scene& s) {
    for (int k = 0; k < 3; ++k) {
      bottom[k] = s.bottom[k];
      top[k] = s.top[k];
      delta[k] = s.delta[k];
      lo[k] = s.lo[k];
      hi[k] = s.hi[k];
    }
  }
  // scalar.h's exact sky: t = clamp((uy + 1) 0.5, 0, 1), then
  // clamp(t == 1 ? top : bottom + t delta, lo, hi).
  void shade(vfloat uy, vfloat out[3]) const {
    const vfloat t = clamp((uy + 1.0f) * 0.5f, 0.0f, 1.0f);
    const vmask at_top = t == 1.0f;
    for (int k = 0; k < 3; ++k) out[k] = clamp(select(at_top, top[k], bottom[k] + t * delta[k]), lo[k], hi[k]);
  }
};

// The colour of one batch (float_spheres.h): the closest hit's shading, the
// sky where nothing was hit.
template <int Shades>
RAYCAST_INLINE void shade(const sky_shader& sky, const closest_hit<Shades>& h, const vfloat u[3],
                          vfloat out[3]) {
  if (none(h.hit)) {
    sky.shade(u[1], out);
    return;
  }
  vfloat hit_colour[3];
  if constexpr ((Shades & normal_shading) != 0) {
    const vfloat f[3] = {h.fx, h.fy, h.fz};
    vfloat n[3];
    for (int k = 0; k < 3; ++k) n[k] = (f[k] + h.t * u[k]) * h.inv_r;
    const vmask back = (n[0] * u[0] + n[1] * u[1]) + n[2] * u[2] >= 0.0f;  // face the ray
    for (int k = 0; k < 3; ++k) hit_colour[k] = (select(back, -n[k], n[k]) + 1.0f) * 0.5f;
  }
  if constexpr (Shades == flat_shading) {
    hit_colour[0] = h.red;
    hit_colour[1] = h.green;
    hit_colour[2] = h.blue;
  } else if constexpr (Shades == (normal_shading | flat_shading)) {
    const vmask flat = h.flat == 1.0f;
    hit_colour[0] = select(flat, h.red, hit_colour[0]);
    hit_colour[1] = select(flat, h.green, hit_colour[1]);
    hit_colour[2] = select(flat, h.blue, hit_colour[2]);
  }
  vfloat sky_colour[3];
  sky.shade(u[1], sky_colour);
  for (int k = 0; k < 3; ++k) out[k] = select(h.hit, hit_colour[k], sky_colour[k]);
}

template <int Shades, bool Float>
void render(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const float_scene& s = *a.scene;
  const sphere_arrays& sp = a.spheres;
  const sky_shader sky(s);
  const int64_t W = s.width;
  // The spheres each row may hit; malloc rather than a container (no
  // standard-library template is instantiated with this instruction set's
  // flags). Without memory, every row tests every sphere.
  uint32_t* const near = static_cast<uint32_t*>(std::malloc(sp.n * sizeof(uint32_t)));
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv = s.height == 1 ? 0.0f : (float(j) - s.mid_row) / s.last_row;  // scalar.h
    const size_t count = near ? spheres_near_row(s, sv, near) : sp.n;  // the others cannot be hit here
    const vfloat row_part[3] = {sv * s.vertical[0], sv * s.vertical[1], sv * s.vertical[2]};
    unsigned char* const out = band.row(r);
    for (int64_t i0 = 0; i0 < W; i0 += N) {
      const int n = W - i0 >= N ? N : int(W - i0);
      // The ray batch: scalar.h's direction, then float_spheres.h's unit vector.
      vfloat d[3];
      for (int k = 0; k < 3; ++k) d[k] = vfloat::load(a.column_part[k] + i0) + row_part[k];
      const vfloat n2 = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
      const vfloat len = sqrt(max(n2, FLT_MIN));
      const vfloat u[3] = {d[0] / len, d[1] / len, d[2] / len};

      closest_hit<Shades> h;
      intersect(sp, near, count, u[0], u[1], u[2], h);
      vfloat c[3];
      shade(sky, h, u, c);

      if constexpr (Float) {
        float* dst = reinterpret_cast<float*>(out) + 3 * i0;
        if (n == N) {
          store_rgbf(dst, c[0], c[1], c[2]);
        } else {
          alignas(64) float tmp[3 * N];
          store_rgbf(tmp, c[0], c[1], c[2]);
          __builtin_memcpy(dst, tmp, sizeof(float) * 3 * size_t(n));
        }
      } else {
        const rgb8_pack p = pack_rgb8<false>(to_int(clamp(c[0], 0.0f, 1.0f) * 255.999f),
                                             to_int(clamp(c[1], 0.0f, 1.0f) * 255.999f),
                                             to_int(clamp(c[2], 0.0f, 1.0f) * 255.999f));
        unsigned char* dst = out + 3 * i0;
        if (n == N) {
          store(dst, p);
        } else {
#ifdef RAYCAST_HAS_MASKED_BYTE_STORE
          store_first(dst, p, n);
#else
          alignas(64) unsigned char tmp[3 * N];
          store(tmp, p);
          __builtin_memcpy(dst, tmp, 3 * size_t(n));
#endif
        }
      }
    }
  }
  std::free(near);
}

template <int Shades>
void render_shades(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  if (band.format == pixel_format::rgb_f32) render<Shades, true>(a, band, r0, r1);
  else render<Shades, false>(a, band, r0, r1);
}

}  // namespace

void render_sphere_rows(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1, bool) {
  const sphere_arrays& sp = a.spheres;
  if (!sp.any_flat) render_shades<normal_shading>(a, band, r0, r1);
  else if (!sp.any_normal) render_shades<flat_shading>(a, band, r0, r1);
  else render_shades<normal_shading | flat_shading>(a, band, r0, r1);
}

}  // namespace raycast::kernels::RAYCAST_ISA
