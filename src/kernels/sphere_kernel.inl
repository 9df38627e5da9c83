// The sphere kernel, written once against the width-generic vector layer and
// compiled per instruction set (sphere_sse2.cpp, sphere_avx2.cpp,
// sphere_avx512.cpp each define RAYCAST_ISA and include their simd/ header
// first), as the sky kernel is.
//
// One batch is vfloat::size pixels of a row (8, or 16 with AVX-512). The rays
// are a structure of arrays in registers (the camera direction d, not
// normalized; the origin is shared by every primary ray and lives in the
// spheres' constants); the spheres are a structure of arrays in memory
// (kernels/float_spheres.h), each sphere's constants broadcast to every lane.
// Closest hit with masks: per lane, the nearest t so far and what shading
// needs of the sphere that gave it. Both precisions perform
// kernels/float_spheres.h's operations in its order, so the output is
// bit-identical to render_scalar.
//
// Left out where the scene does not need it: the frame's row index lists,
// per row, the spheres that may come near it (kernels/culling.h, built once
// by the renderer); each row turns its entries into a list per batch
// (batch_culler, compiled once), and a batch tests only those; a
// batch with none computes the sky alone, with no division but the sky's; a
// sphere that no lane of the batch can hit (every disc < 0) costs no square
// root or division; a batch where every lane hit something computes no sky; a
// flat-shaded scene tracks no centres and computes no normals, a
// normal-shaded one tracks no colours.
//
// Many samples per pixel (render_samples, below; every scene, the sky alone
// included) run the same batches with each sample as one pass, the lists
// widened to the pixels' squares of samples.
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "kernels/kernel.h"
#include "kernels/sampled_sky.h"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;

// Samples per pass of the sampled path (render_samples): two overlap their
// dependency chains where the registers hold both passes' rays and hits
// (AVX-512's 32 zmm, AVX2's 16 ymm, NEON's 32 q registers as 8-lane pairs);
// SSE2's 16 xmm registers, two per vector, do not, and it takes one
// (sphere_sse2.cpp; on `world` one sample at a time is 7 % faster there).
#ifndef RAYCAST_SAMPLES_PER_PASS
#define RAYCAST_SAMPLES_PER_PASS 2
#endif
constexpr int samples_per_pass = RAYCAST_SAMPLES_PER_PASS;

// Which shadings the scene's spheres use (bit 0: normal, bit 1: flat, bit 2:
// lit). A scene with lit spheres runs the general path, all three.
constexpr int normal_shading = 1;
constexpr int flat_shading = 2;
constexpr int lit_shading = 4;
constexpr int all_shadings = normal_shading | flat_shading | lit_shading;
// More than one shading: each hit carries its sphere's kind.
template <int Shades>
constexpr bool mixed = Shades != normal_shading && Shades != flat_shading;

// The closest hit per lane, and what shading reads of its sphere.
template <int Shades>
struct closest_hit {
  vmask hit{};                 // all false
  vfloat t = FLT_MAX;          // float_spheres.h: closest starts at FLT_MAX
  vfloat s = 0.0f;             // the hit's s, in its sphere's unit
  vfloat fx = 0.0f, fy = 0.0f, fz = 0.0f, inv_r = 0.0f;  // normal shading
  vfloat inside = 0.0f;  // 1 where the camera is inside the hit sphere (scenes with such a sphere)
  vfloat red = 0.0f, green = 0.0f, blue = 0.0f;  // flat and lit shading
  vfloat kind = 0.0f;  // float_spheres::kind, for mixed scenes
};

// The batch's rays: d and what every sphere reads of it.
struct rays {
  vfloat d[3];
  vfloat n2;  // |d|^2 in scalar.h's order
  // 1 / n2, computed the first time a far sphere needs it: a division is a
  // large part of a batch's cost.
  vfloat inv_n2() {
    if (!have_inv_) {
      inv_ = 1.0f / n2;
      have_inv_ = true;
    }
    return inv_;
  }

 private:
  vfloat inv_ = 0.0f;
  bool have_inv_ = false;
};

// Records sphere k's hit where m (its s and t already chosen) in h.
template <int Shades>
RAYCAST_INLINE void record(const sphere_arrays& sp, size_t k, vmask m, vfloat s, closest_hit<Shades>& h) {
  if (none(h.hit)) {  // the first sphere hit: lanes it misses never read these
    h.hit = m;
    if constexpr ((Shades & normal_shading) != 0) {
      h.s = s;
      h.fx = sp.rec[k].fx;
      h.fy = sp.rec[k].fy;
      h.fz = sp.rec[k].fz;
      h.inv_r = sp.rec[k].inv_r;
      if (sp.any_inside) h.inside = sp.rec[k].inside ? 1.0f : 0.0f;
    }
    if constexpr ((Shades & flat_shading) != 0) {
      h.red = sp.red[k];
      h.green = sp.green[k];
      h.blue = sp.blue[k];
      if constexpr (mixed<Shades>) h.kind = sp.kind[k];
    }
    return;
  }
  h.hit = h.hit | m;
  if constexpr ((Shades & normal_shading) != 0) {
    h.s = select(m, s, h.s);
    h.fx = select(m, vfloat(sp.rec[k].fx), h.fx);
    h.fy = select(m, vfloat(sp.rec[k].fy), h.fy);
    h.fz = select(m, vfloat(sp.rec[k].fz), h.fz);
    h.inv_r = select(m, vfloat(sp.rec[k].inv_r), h.inv_r);
    if (sp.any_inside) h.inside = select(m, vfloat(sp.rec[k].inside ? 1.0f : 0.0f), h.inside);
  }
  if constexpr ((Shades & flat_shading) != 0) {
    h.red = select(m, vfloat(sp.red[k]), h.red);
    h.green = select(m, vfloat(sp.green[k]), h.green);
    h.blue = select(m, vfloat(sp.blue[k]), h.blue);
    if constexpr (mixed<Shades>) h.kind = select(m, vfloat(sp.kind[k]), h.kind);
  }
}

// Tests the spheres list[0 .. count) (every sphere, 0 .. count, when list is
// null) against M independent ray batches at once, each step written for all
// M before the next (the sampled path takes samples_per_pass samples at a
// time: their long dependency chains overlap).
template <int Shades, int M>
RAYCAST_INLINE void intersect(const sphere_arrays& sp, const uint32_t* list, size_t count, rays (&r)[M],
                              closest_hit<Shades> (&h)[M], const float* fz_dz = nullptr) {
  for (size_t x = 0; x < count; ++x) {
    const size_t k = list ? list[x] : x;
    const vfloat fx = sp.rec[k].fx, fy = sp.rec[k].fy, fz = sp.rec[k].fz;
    vfloat b[M], disc[M];
    vmask can_hit[M];
    bool any_can = false;
    if (fz_dz) {  // every ray's d.z is the same: f.z d.z is the sphere's
      for (int u = 0; u < M; ++u) b[u] = (fx * r[u].d[0] + fy * r[u].d[1]) + vfloat(fz_dz[k]);
    } else {
      for (int u = 0; u < M; ++u) b[u] = (fx * r[u].d[0] + fy * r[u].d[1]) + fz * r[u].d[2];
    }
    if (sp.rec[k].near) {
      for (int u = 0; u < M; ++u) disc[u] = b[u] * b[u] - r[u].n2 * vfloat(sp.rec[k].c);
    } else {
      for (int u = 0; u < M; ++u) {
        const vfloat kb = b[u] * r[u].inv_n2();
        const vfloat vx = fx - kb * r[u].d[0], vy = fy - kb * r[u].d[1], vz = fz - kb * r[u].d[2];
        disc[u] = r[u].n2 * (vfloat(sp.rec[k].r2) - ((vx * vx + vy * vy) + vz * vz));
      }
    }
    for (int u = 0; u < M; ++u) {
      can_hit[u] = disc[u] >= 0.0f;
      any_can = any_can || any(can_hit[u]);
    }
    if (!any_can) continue;  // no lane can hit it: no sqrt, no divide
    vfloat q[M], s[M];
    // The lanes where disc < 0 are not read: no max(disc, 0) here.
    for (int u = 0; u < M; ++u) q[u] = -(b[u] + copysign(sqrt(disc[u]), b[u]));
    for (int u = 0; u < M; ++u) s[u] = vfloat(sp.rec[k].c) / q[u];
    for (int u = 0; u < M; ++u) {
      if (sp.rec[k].inside) {  // the far root where the near one is behind
        const vmask behind = can_hit[u] & !(s[u] >= 0.0f);
        if (any(behind)) s[u] = select(behind, q[u] / r[u].n2, s[u]);
      }
      const vfloat t = s[u] * vfloat(sp.rec[k].scale);
      const vmask m = can_hit[u] & (s[u] >= 0.0f) & (t <= h[u].t);
      h[u].t = select(m, t, h[u].t);
      record(sp, k, m, s[u], h[u]);
    }
  }
}

// One ray batch (the one-sample path): the same steps as above for M = 1,
// written without arrays -- SSE2's two-half vectors in one-element arrays
// are not kept in registers by GCC 12 (+40 % on sse2/world).
template <int Shades>
RAYCAST_INLINE void intersect(const sphere_arrays& sp, const uint32_t* list, size_t count, rays& r,
                              closest_hit<Shades>& h) {
  for (size_t x = 0; x < count; ++x) {
    const size_t k = list ? list[x] : x;
    const vfloat fx = sp.rec[k].fx, fy = sp.rec[k].fy, fz = sp.rec[k].fz;
    const vfloat b = (fx * r.d[0] + fy * r.d[1]) + fz * r.d[2];
    vfloat disc;
    if (sp.rec[k].near) {
      disc = b * b - r.n2 * vfloat(sp.rec[k].c);
    } else {
      const vfloat kb = b * r.inv_n2();
      const vfloat vx = fx - kb * r.d[0], vy = fy - kb * r.d[1], vz = fz - kb * r.d[2];
      disc = r.n2 * (vfloat(sp.rec[k].r2) - ((vx * vx + vy * vy) + vz * vz));
    }
    const vmask can_hit = disc >= 0.0f;
    if (none(can_hit)) continue;
    const vfloat q = -(b + copysign(sqrt(max(disc, 0.0f)), b));
    vfloat s = vfloat(sp.rec[k].c) / q;
    if (sp.rec[k].inside) {  // the far root where the near one is behind
      const vmask behind = can_hit & !(s >= 0.0f);
      if (any(behind)) s = select(behind, q / r.n2, s);
    }
    const vfloat t = s * vfloat(sp.rec[k].scale);
    const vmask m = can_hit & (s >= 0.0f) & (t <= h.t);
    h.t = select(m, t, h.t);
    record(sp, k, m, s, h);
  }
}

// The sky's constants in registers, loaded once per call, and the sky
// kernel's shortcuts `channels` and `clamps` (render/plan.h), which the plan
// decides for sphere scenes too.
struct sky_shader {
  vfloat bottom[3], top[3], delta[3], lo[3], hi[3];
  bool constant[3];
  bool lerp_exact;
  explicit sky_shader(const kernel_args& a) : lerp_exact(a.lerp_exact) {
    const float_scene& s = *a.scene;
    for (int k = 0; k < 3; ++k) {
      bottom[k] = s.bottom[k];
      top[k] = s.top[k];
      delta[k] = s.delta[k];
      lo[k] = s.lo[k];
      hi[k] = s.hi[k];
      constant[k] = a.constant[k];
    }
  }
  // scalar.h's exact sky: uy = d.y / sqrt(max(n2, FLT_MIN)),
  // t = clamp((uy + 1) 0.5, 0, 1), then clamp(t == 1 ? top : bottom + t delta, lo, hi).
  // |d.y| <= sqrt(fl(n2)), so t is in [0, 1] already and its clamp is left
  // out (as in sky_kernel.inl); so are a constant channel's lerp and, when
  // the lerp is exact at its ends, its select and clamp.
  void shade(const rays& r, vfloat out[3]) const {
    const vfloat uy = r.d[1] / sqrt(max(r.n2, FLT_MIN));
    const vfloat t = (uy + 1.0f) * 0.5f;
    for (int k = 0; k < 3; ++k) {
      if (constant[k]) out[k] = bottom[k];
      else if (lerp_exact) out[k] = bottom[k] + t * delta[k];
      else out[k] = clamp(select(t == 1.0f, top[k], bottom[k] + t * delta[k]), lo[k], hi[k]);
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
RAYCAST_INLINE void hit_colour(const sphere_arrays& sp, const closest_hit<Shades>& h, const rays& r,
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
  hit_colour(sp, h, r, hit);
  if (all(h.hit)) {
    for (int k = 0; k < 3; ++k) out[k] = hit[k];
    return;
  }
  vfloat sky_colour[3];
  sky.shade(r, sky_colour);
  for (int k = 0; k < 3; ++k) out[k] = select(h.hit, hit[k], sky_colour[k]);
}

// Stores n pixels of a batch at column i0; Reversed, all N with their lanes
// in the opposite order (the mirrored batch).
template <bool Float, bool Reversed = false>
RAYCAST_INLINE void store_batch(unsigned char* out, int64_t i0, int n, const vfloat c[3]) {
  if constexpr (Float) {
    float* dst = reinterpret_cast<float*>(out) + 3 * i0;
    if constexpr (Reversed) {
      store_rgbf(dst, reverse(c[0]), reverse(c[1]), reverse(c[2]));
    } else if (n == N) {
      store_rgbf(dst, c[0], c[1], c[2]);
    } else {
      alignas(64) float tmp[3 * N];
      store_rgbf(tmp, c[0], c[1], c[2]);
      __builtin_memcpy(dst, tmp, sizeof(float) * 3 * size_t(n));
    }
  } else {
    const rgb8_pack p = pack_rgb8<Reversed>(to_int(clamp(c[0], 0.0f, 1.0f) * 255.999f),
                                            to_int(clamp(c[1], 0.0f, 1.0f) * 255.999f),
                                            to_int(clamp(c[2], 0.0f, 1.0f) * 255.999f));
    unsigned char* dst = out + 3 * i0;
    if (Reversed || n == N) {
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

// Stores the lanes of a batch at column i0 that lie in the band's column
// window [c0, c1) (image_band); row points at column c0.
template <bool Float>
RAYCAST_INLINE void store_window(unsigned char* row, int64_t i0, int64_t c0, int64_t c1, const vfloat c[3]) {
  const int64_t lo = i0 > c0 ? i0 : c0, hi = i0 + N < c1 ? i0 + N : c1;
  if (lo == i0) {
    store_batch<Float>(row, i0 - c0, int(hi - lo), c);
    return;
  }
  constexpr size_t bpp = Float ? 12 : 3;
  alignas(64) unsigned char tmp[bpp * N];
  store_batch<Float>(tmp, 0, N, c);
  __builtin_memcpy(row + bpp * size_t(lo - c0), tmp + bpp * size_t(lo - i0), bpp * size_t(hi - lo));
}

template <int Shades, bool Float, bool Lanes>
void render(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const float_scene& s = *a.scene;
  const sphere_arrays& sp = a.spheres;
  const sky_shader sky(a);
  const int64_t W = s.width, c0 = band.col_begin, c1 = band.cols_end(W);
  const int64_t batches = (W + N - 1) / N;
  // The batches that hold the band's columns.
  const int64_t first_batch = c0 / N, end_batch = (c1 + N - 1) / N;
  batch_culler lists(s, a.row_most, N, 0.0);
  const bool mirror = a.mirror && lists.ok() && band.whole_rows(W);
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv = s.height == 1 ? 0.0f : (float(j) - s.mid_row) / s.last_row;  // scalar.h
    if (lists.ok()) lists.row(sv, a.row_list + a.row_first[r], size_t(a.row_first[r + 1] - a.row_first[r]));
    const int64_t run = lists.ok() ? lists.run_length() : batches;
    const vfloat row_part[3] = {sv * s.vertical[0], sv * s.vertical[1], sv * s.vertical[2]};
    unsigned char* const out = band.row(r);
    const auto tests_of = [&](int64_t b) -> size_t { return lists.ok() ? lists.tests(b) : sp.n; };
    // Shortcut `lanes` (the axis-aligned camera): every column's d.y and d.z
    // are the first column's, bit for bit (scalar.h: centre + su * 0), so
    // they and their squares are per row.
    const float dy = a.column_part[1][0] + sv * s.vertical[1], dz = a.column_part[2][0] + sv * s.vertical[2];
    const vfloat row_y = dy, row_z = dz, row_y2 = dy * dy, row_z2 = dz * dz;
    const auto rays_at = [&](int64_t i0) {
      rays ry;
      if constexpr (Lanes) {
        ry.d[0] = vfloat::load(a.column_part[0] + i0) + row_part[0];
        ry.d[1] = row_y;
        ry.d[2] = row_z;
        ry.n2 = (ry.d[0] * ry.d[0] + row_y2) + row_z2;
      } else {
        for (int k = 0; k < 3; ++k) ry.d[k] = vfloat::load(a.column_part[k] + i0) + row_part[k];
        ry.n2 = (ry.d[0] * ry.d[0] + ry.d[1] * ry.d[1]) + ry.d[2] * ry.d[2];
      }
      return ry;
    };
    // Shortcut `mirror` (the lesson camera: the sky is symmetric about the
    // row's middle, bit for bit): the first `ends` batches are sky only, and
    // so are the columns they mirror to; each is shaded once and stored at
    // both ends. It needs the whole row's lists at once (one run).
    int64_t ends = 0;
    if (mirror && run == batches) {
      lists.build(0, batches);
      int64_t lead = 0, trail = 0;
      while (lead < batches && tests_of(lead) == 0) ++lead;
      while (trail < batches - lead && tests_of(batches - 1 - trail) == 0) ++trail;
      const int64_t sky_from = lead == batches ? 0 : (batches - trail) * N;  // sky to the row's end
      const int64_t by_right = (W - N - sky_from) / N + 1, by_middle = (W - 2 * N) / (2 * N) + 1;
      ends = W < 2 * N ? 0 : (lead < by_right ? lead : by_right);
      ends = ends < by_middle ? ends : by_middle;
      if (ends < 0) ends = 0;
      for (int64_t b = 0; b < ends; ++b) {
        vfloat c[3];
        sky.shade(rays_at(b * N), c);
        store_batch<Float>(out, b * N, N, c);
        store_batch<Float, true>(out, W - b * N - N, N, c);
      }
    }
    for (int64_t b0 = ends > first_batch ? ends : first_batch; b0 < end_batch; b0 += run) {
      const int64_t b1 = b0 + run < end_batch ? b0 + run : end_batch;
      const bool built = mirror && run == batches;  // above, from batch 0
      if (!built && lists.ok()) lists.build(b0, b1);
      for (int64_t b = b0; b < b1; ++b) {
        const int64_t i0 = b * N;
        if (i0 >= W - ends * N) break;  // the mirrored end, already stored
        // The ray batch: scalar.h's direction and its squared length.
        rays ry = rays_at(i0);
        const size_t tests = tests_of(b);
        vfloat c[3];
        if (tests == 0) {
          sky.shade(ry, c);  // no sphere comes near these rays
        } else {
          const uint32_t* list = lists.ok() ? lists.list(b) : nullptr;
          closest_hit<Shades> h;
          intersect(sp, list, tests, ry, h);
          shade(sky, sp, h, ry, c);
        }
        store_window<Float>(out, i0, c0, c1, c);
      }
    }
  }
}

// Many samples per pixel (scene/sampler.h; the order is kernels/scalar.h's
// scalar_pixel_samples). A batch is still N pixels of a row, each lane one
// pixel: the batch's sphere list holds the spheres any ray of its pixels'
// squares may come near (the culling radii widened by the scene's
// pixel_spread), and each sample is one pass of the one-sample batch --
// offsets, direction, intersection, normal -- added to a per-lane sum in
// sample order. The random numbers are drawn per lane with the vector
// layer's integer operations.
template <int Shades, sampler_kind K>
void render_samples(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const float_scene& s = *a.scene;
  const sphere_arrays& sp = a.spheres;
  const sampling::sample_plan& plan = *a.samples;
  const bool f32 = band.format == pixel_format::rgb_f32;
  const int64_t W = s.width, c0 = band.col_begin, c1 = band.cols_end(W);
  const int64_t batches = (W + N - 1) / N;
  const int64_t first_batch = c0 / N, end_batch = (c1 + N - 1) / N;
  batch_culler lists(s, a.row_most, N, s.pixel_spread);
  const vfloat count = float(plan.count);
  // scalar.h: the steps of one offset count, du and dv times the sampler's
  // unit (exact), times horizontal and vertical.
  const float du = s.du * sampling::offset_unit<K>, dv = s.dv * sampling::offset_unit<K>;
  vfloat step_x[3], step_y[3];
  for (int k = 0; k < 3; ++k) {
    step_x[k] = du * s.horizontal[k];
    step_y[k] = dv * s.vertical[k];
  }
  // The lesson's camera (centre = (+0, +0, -f), horizontal = (h, 0, 0),
  // vertical = (0, v, 0)): scalar.h's d.x = (base.x + xi step_x.x) + eta 0
  // is base.x + xi step_x.x bit for bit (adding +0 leaves a sum that is
  // never -0 unchanged: base.x starts from centre.x = +0), d.y = base.y + eta step_y.y
  // likewise, and d.z = base.z = -f exactly.
  const bool lesson = s.axis_aligned_camera && s.centre[0] == 0.0f && s.centre[1] == 0.0f &&
                      !std::signbit(s.centre[0]) && !std::signbit(s.centre[1]) && s.centre[2] != 0.0f;
  const vfloat z2 = s.centre[2] * s.centre[2];
  // The lesson's camera: each sphere's f.z d.z, once (raw memory, as
  // batch_lists; without it, intersect forms f.z d.z per ray, the same bits).
  struct products {
    float* v = nullptr;
    ~products() { std::free(v); }
  } fz_dz_table;
  if (lesson) fz_dz_table.v = static_cast<float*>(std::malloc(sp.n * sizeof(float) + 1));
  const float* const fz_dz = fz_dz_table.v;
  if (fz_dz_table.v)
    for (size_t k = 0; k < sp.n; ++k) fz_dz_table.v[k] = sp.rec[k].fz * s.centre[2];
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv_j = s.height == 1 ? 0.0f : (float(j) - s.mid_row) / s.last_row;  // scalar.h
    if (lists.ok()) lists.row(sv_j, a.row_list + a.row_first[r], size_t(a.row_first[r + 1] - a.row_first[r]));
    const int64_t run = lists.ok() ? lists.run_length() : batches;
    unsigned char* const out = band.row(r);
    for (int64_t b0 = first_batch; b0 < end_batch; b0 += run) {
      const int64_t b1 = b0 + run < end_batch ? b0 + run : end_batch;
      if (lists.ok()) lists.build(b0, b1);
      for (int64_t b = b0; b < b1; ++b) {
        const int64_t i0 = b * N;
        const size_t tests = lists.ok() ? lists.tests(b) : sp.n;
        const uint32_t* list = lists.ok() && tests > 0 ? lists.list(b) : nullptr;
        const vuint column = vuint::iota(uint32_t(i0));
        const vfloat su_i = W == 1 ? vfloat(0.0f) : (to_float(column) - s.mid_col) / s.last_col;  // scalar.h
        vfloat base[3];  // the pixels' one-sample directions
        for (int k = 0; k < 3; ++k) base[k] = (s.centre[k] + su_i * s.horizontal[k]) + sv_j * s.vertical[k];
        const sampling::pixel_seeds<vuint> seeds = sampling::seeds_for<K>(plan, column, uint32_t(j));
        // Per lane (scalar.h): the flat colours' sum, the normals' sum and
        // count, the sky's sum of u and count (kernels/sampled_sky.h).
        vfloat flat[3] = {0.0f, 0.0f, 0.0f}, normals[3] = {0.0f, 0.0f, 0.0f}, normal_count = 0.0f;
        vfloat sky_sum = 0.0f, sky_count = 0.0f;
        // M samples at a time (samples_per_pass, then one at a time for
        // the rest), each step for all M before the next; their sums in
        // sample order. Always inlined: GCC 12 kept SSE2's two-sample pass
        // out of line (+40 % per sample).
        const auto samples = [&]<int M>(uint32_t t0) __attribute__((always_inline)) {
          rays ry[M];
          for (int u = 0; u < M; ++u) {
            vfloat xi, eta;  // counts of the sampler's offset_unit
            sampling::offset_counts<K>(plan, seeds, t0 + uint32_t(u), xi, eta);
            if (lesson) {
              ry[u].d[0] = base[0] + xi * step_x[0];
              ry[u].d[1] = base[1] + eta * step_y[1];
              ry[u].d[2] = base[2];
              ry[u].n2 = (ry[u].d[0] * ry[u].d[0] + ry[u].d[1] * ry[u].d[1]) + z2;
            } else {
              for (int k = 0; k < 3; ++k) ry[u].d[k] = (base[k] + xi * step_x[k]) + eta * step_y[k];
              ry[u].n2 = (ry[u].d[0] * ry[u].d[0] + ry[u].d[1] * ry[u].d[1]) + ry[u].d[2] * ry[u].d[2];
            }
          }
          if (tests == 0) {  // no sphere comes near these rays
            vfloat u_of[M];
            for (int u = 0; u < M; ++u) u_of[u] = sampled::sky_u<vfloat, vuint>(ry[u].d[1], ry[u].n2);
            for (int u = 0; u < M; ++u) {
              sky_sum = sky_sum + u_of[u];
              sky_count = sky_count + 1.0f;
            }
            return;
          }
          closest_hit<Shades> h[M];
          // One sphere (most batches that test any): its own copy, in which
          // the compiler knows the closest hit starts empty.
          if (tests == 1) intersect<Shades, M>(sp, list, 1, ry, h, fz_dz);
          else intersect<Shades, M>(sp, list, tests, ry, h, fz_dz);
          // A lane adds only what its sample gave: + 0 leaves a sum that is
          // never -0 unchanged, so the other lanes' adds change nothing.
          for (int u = 0; u < M; ++u) {
            if (any(h[u].hit)) {
              const bool every = all(h[u].hit);
              vfloat n[3];
              if constexpr ((Shades & normal_shading) != 0) {
                vmask normal = h[u].hit;
                if constexpr (mixed<Shades>) normal = normal & (h[u].kind == shading_kind::normal);
                hit_normal(sp, h[u], ry[u], n);
                if constexpr (Shades == normal_shading) {
                  for (int k = 0; k < 3; ++k) normals[k] = normals[k] + (every ? n[k] : select(normal, n[k], 0.0f));
                } else {
                  for (int k = 0; k < 3; ++k) normals[k] = normals[k] + select(normal, n[k], 0.0f);
                  normal_count = normal_count + select(normal, 1.0f, 0.0f);
                }
              }
              if constexpr ((Shades & flat_shading) != 0) {  // flat and lit colours
                vmask coloured = h[u].hit;
                if constexpr (mixed<Shades>) coloured = coloured & !(h[u].kind == shading_kind::normal);
                vfloat c[3] = {h[u].red, h[u].green, h[u].blue};
                if constexpr (Shades == all_shadings) {
                  const vmask lit = h[u].hit & (h[u].kind == shading_kind::lit);
                  if (any(lit)) {
                    const vfloat light = headlight(n, ry[u].d, ry[u].n2);
                    for (int k = 0; k < 3; ++k) c[k] = select(lit, c[k] * light, c[k]);
                  }
                }
                for (int k = 0; k < 3; ++k) flat[k] = flat[k] + select(coloured, c[k], 0.0f);
              }
              if (every) continue;
            }
            const vfloat sky = sampled::sky_u<vfloat, vuint>(ry[u].d[1], ry[u].n2);
            sky_sum = sky_sum + select(h[u].hit, 0.0f, sky);
            sky_count = sky_count + select(h[u].hit, 0.0f, 1.0f);
          }
        };
        uint32_t t = 0;
        for (; t + samples_per_pass <= plan.count; t += samples_per_pass)
          samples.template operator()<samples_per_pass>(t);
        for (; t < plan.count; ++t) samples.template operator()<1>(t);
        // A normal-shaded scene's normal count is what the sky did not take (exact: below 2^24).
        if constexpr (Shades == normal_shading) normal_count = count - sky_count;
        vfloat c[3];
        for (int k = 0; k < 3; ++k)
          c[k] = ((flat[k] + (normals[k] + normal_count) * 0.5f) + (sky_count * s.sky_mid[k] + sky_sum * s.sky_half[k])) / count;
        if (f32) store_window<true>(out, i0, c0, c1, c);
        else store_window<false>(out, i0, c0, c1, c);
      }
    }
  }
}

template <int Shades>
void render_sampled(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  switch (a.samples->kind) {
    case sampler_kind::random: render_samples<Shades, sampler_kind::random>(a, band, r0, r1); break;
    case sampler_kind::stratified: render_samples<Shades, sampler_kind::stratified>(a, band, r0, r1); break;
    case sampler_kind::sobol: render_samples<Shades, sampler_kind::sobol>(a, band, r0, r1); break;
  }
}

template <int Shades>
void render_shades(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  if (a.samples) render_sampled<Shades>(a, band, r0, r1);
  else if (band.format == pixel_format::rgb_f32) {
    if (a.lanes) render<Shades, true, true>(a, band, r0, r1);
    else render<Shades, true, false>(a, band, r0, r1);
  } else {
    if (a.lanes) render<Shades, false, true>(a, band, r0, r1);
    else render<Shades, false, false>(a, band, r0, r1);
  }
}

}  // namespace

void render_sphere_rows(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1, bool) {
  const sphere_arrays& sp = a.spheres;
  if (sp.any_lit) render_shades<all_shadings>(a, band, r0, r1);
  else if (!sp.any_flat) render_shades<normal_shading>(a, band, r0, r1);
  else if (!sp.any_normal) render_shades<flat_shading>(a, band, r0, r1);
  else render_shades<normal_shading | flat_shading>(a, band, r0, r1);
}

}  // namespace raycast::kernels::RAYCAST_ISA
