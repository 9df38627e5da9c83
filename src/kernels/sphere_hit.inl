// The sphere kernel's intersection (float_spheres.h), for one ray batch or M at once.
#pragma once
#include <cfloat>
#include <cstddef>
#include <cstdint>

#include "kernels/target.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// Which shadings the scene's spheres use; a scene with lit spheres runs all three.
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
  vuint index = vuint(0u);     // the hit sphere's index in the scene (the tie rule)
  vfloat s = 0.0f;             // the hit's s, in its sphere's unit
  vfloat fx = 0.0f, fy = 0.0f, fz = 0.0f, inv_r = 0.0f;  // normal shading
  vfloat inside = 0.0f;  // 1 where the camera is inside the hit sphere
  vfloat red = 0.0f, green = 0.0f, blue = 0.0f;  // flat and lit shading
  vfloat kind = 0.0f;  // float_spheres::kind, for mixed scenes
};

struct rays {
  vfloat d[3];
  vfloat n2;  // |d|^2 in scalar.h's order
  vfloat px = 0.0f, py = 0.0f;  // an orthographic ray's start on the image plane (float_scene.h)

  // n2 from d, guarded where the frame has short directions (centre_unit: float_scene's, or null
  // without tiny_directions). A lane whose n2 is below 2^-64 has its d scaled by 2^64: exact, and
  // nothing a ray shows changes (hits compare s along one ray; normal and sky are homogeneous in
  // d), but no n2 is denormal, on any target or under FTZ/DAZ. A lane whose d is 0 even so is the
  // centre ray of a centre below float's range of the viewport: its direction is centre_unit.
  RAYCAST_INLINE void set_length(const float* centre_unit) {
    n2 = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
    if (!centre_unit) return;
    const vmask tiny = !(n2 >= 0x1p-64f);
    if (none(tiny)) return;
    for (int k = 0; k < 3; ++k) d[k] = select(tiny, d[k] * 0x1p64f, d[k]);
    n2 = select(tiny, (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2], n2);
    const vmask zero = n2 <= vfloat(0.0f);
    if (none(zero)) return;
    for (int k = 0; k < 3; ++k) d[k] = select(zero, vfloat(centre_unit[k]), d[k]);
    n2 = select(zero, (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2], n2);
  }
  // 1 / n2, the first time a far sphere needs it.
  vfloat inv_n2() {
    if (!have_inv_) {
      inv_ = 1.0f / n2;
      have_inv_ = true;
    }
    return inv_;
  }
  // |d|, the first time a depth-ordered walk asks whether it may stop.
  vfloat length() {
    if (!have_len_) {
      len_ = sqrt(n2);
      have_len_ = true;
    }
    return len_;
  }

 private:
  vfloat inv_ = 0.0f, len_ = 0.0f;
  bool have_inv_ = false, have_len_ = false;
};

// Records sphere k's hit in h where m; the normal is (f + s d) inv_r (orthographic: s = 0).
template <int Shades>
RAYCAST_INLINE void record(const kernel_spheres& sp, size_t k, vmask m, vfloat s, const vfloat (&f)[3],
                           closest_hit<Shades>& h) {
  const vuint index = vuint(sp.scene_index(k));
  if (none(h.hit)) {  // the first sphere hit: lanes it misses never read these
    h.hit = m;
    if (sp.track_index) h.index = index;
    if constexpr ((Shades & normal_shading) != 0) {
      h.s = s;
      h.fx = f[0];
      h.fy = f[1];
      h.fz = f[2];
      h.inv_r = sp.rec[k].inv_r;
      if (sp.any_inside) h.inside = sp.rec[k].inside ? 1.0f : 0.0f;
    }
    if constexpr ((Shades & flat_shading) != 0) {
      const size_t c = sp.look(k);
      h.red = sp.red[c];
      h.green = sp.green[c];
      h.blue = sp.blue[c];
      if constexpr (mixed<Shades>) h.kind = sp.kind[c];
    }
    return;
  }
  h.hit = h.hit | m;
  if (sp.track_index) h.index = select(m, index, h.index);
  if constexpr ((Shades & normal_shading) != 0) {
    h.s = select(m, s, h.s);
    h.fx = select(m, f[0], h.fx);
    h.fy = select(m, f[1], h.fy);
    h.fz = select(m, f[2], h.fz);
    h.inv_r = select(m, vfloat(sp.rec[k].inv_r), h.inv_r);
    if (sp.any_inside) h.inside = select(m, vfloat(sp.rec[k].inside ? 1.0f : 0.0f), h.inside);
  }
  if constexpr ((Shades & flat_shading) != 0) {
    const size_t c = sp.look(k);
    h.red = select(m, vfloat(sp.red[c]), h.red);
    h.green = select(m, vfloat(sp.green[c]), h.green);
    h.blue = select(m, vfloat(sp.blue[c]), h.blue);
    if constexpr (mixed<Shades>) h.kind = select(m, vfloat(sp.kind[c]), h.kind);
  }
}

// Sphere e's discriminant (float_spheres.h: textbook where near, Hearn & Baker where far).
RAYCAST_INLINE vfloat discriminant(const sphere_record& e, rays& r, vfloat fx, vfloat fy, vfloat fz, vfloat b) {
  if (e.near) return b * b - r.n2 * vfloat(e.c);
  const vfloat kb = b * r.inv_n2();
  const vfloat vx = fx - kb * r.d[0], vy = fy - kb * r.d[1], vz = fz - kb * r.d[2];
  return r.n2 * (vfloat(e.r2) - ((vx * vx + vy * vy) + vz * vz));
}

// Sphere k's hit at s, t where `ahead`, kept where nearer than the closest hit, or as near and
// later in the scene (the tie rule: the float scene's order need not be the scene's).
template <int Shades>
RAYCAST_INLINE void keep_nearer(const kernel_spheres& sp, size_t k, vmask ahead, vfloat s, vfloat t,
                                const vfloat (&f)[3], closest_hit<Shades>& h) {
  vmask m;
  if (sp.order) {  // a reordered scene: ties by the index in the scene
    m = ahead & !(t >= h.t);
    const vmask tie = ahead & (t == h.t);
    if (any(tie)) m = m | (tie & ((!h.hit) | (vuint(sp.scene_index(k)) > h.index)));
  } else {  // the scene's own order: the later sphere is the one tested later
    m = ahead & (t <= h.t);
  }
  h.t = select(m, t, h.t);
  record(sp, k, m, s, f, h);
}

// Where sphere k can hit: its nearest root not behind (lanes with disc < 0 unread: no max(disc, 0)).
template <int Shades>
RAYCAST_INLINE void take_nearest(const kernel_spheres& sp, size_t k, rays& r, vfloat b, vfloat disc, vmask can_hit,
                                 closest_hit<Shades>& h) {
  const sphere_record& e = sp.rec[k];
  const vfloat q = -(b + copysign(sqrt(disc), b));
  vfloat s = vfloat(e.c) / q;
  if (e.inside) {  // the far root where the near one is behind
    const vmask behind = can_hit & !(s >= 0.0f);
    if (any(behind)) s = select(behind, q / r.n2, s);
  }
  const vfloat f[3] = {e.fx, e.fy, e.fz};
  keep_nearer(sp, k, can_hit & (s >= 0.0f), s, s * vfloat(e.scale), f, h);
}

// An orthographic camera's rays (float_spheres.h): no term as large as the camera's distance
// enters the sum that comes out as small as the radius. The normal's offset from the centre,
// (dx, dy, -+sqrt(disc)), is turned from the camera's axes to the world's here.
template <int Shades>
RAYCAST_INLINE void take_nearest_ortho(const kernel_spheres& sp, size_t k, const rays& r, closest_hit<Shades>& h) {
  const sphere_record& e = sp.rec[k];
  const vfloat dx = r.px * vfloat(e.c) - vfloat(e.fx), dy = r.py * vfloat(e.c) - vfloat(e.fy);
  const vfloat disc = vfloat(e.r2) - (dx * dx + dy * dy);
  const vmask can_hit = disc >= 0.0f;
  if (none(can_hit)) return;
  const vfloat sq = sqrt(disc);
  vfloat s = vfloat(e.fz) - sq, along = -sq;
  vmask ahead = can_hit;
  if (e.inside) {  // the far root where the near one is behind the plane; none where both are
    const vmask behind = can_hit & !(s >= 0.0f);
    s = select(behind, vfloat(e.fz) + sq, s);
    along = select(behind, sq, along);
    ahead = can_hit & (s >= 0.0f);
  }
  vfloat f[3] = {0.0f, 0.0f, 0.0f};
  if constexpr ((Shades & normal_shading) != 0)
    for (int j = 0; j < 3; ++j) f[j] = (dx * vfloat(sp.axes[0][j]) + dy * vfloat(sp.axes[1][j])) + along * vfloat(sp.axes[2][j]);
  keep_nearer(sp, k, ahead, vfloat(0.0f), s * vfloat(e.scale), f, h);
}

// A depth-ordered walk: whether every lane has hit something nearer than sphere e, and so than
// every sphere after it, can be: t |d| below e's bucket's key (an orthographic t is a depth already).
// The key's 2^-15 margin exceeds both distances' rounding (README.md), so a sphere left out would
// be strictly farther: never a tie, the same bits as a walk over the whole list.
template <bool Ortho, int Shades>
RAYCAST_INLINE bool nearer_than(const kernel_spheres& sp, const sphere_record& e, rays& r, const closest_hit<Shades>& h) {
  if (!all(h.hit)) return false;
  if constexpr (Ortho) return all(!(h.t >= vfloat(sp.depth_key[e.depth])));
  return all(!(h.t * r.length() >= vfloat(sp.depth_key[e.depth])));
}

// Candidates are scattered: the record six ahead is fetched now, a batch's first six the batch before.
constexpr size_t prefetch_distance = 6;
RAYCAST_INLINE void prefetch_sphere(const kernel_spheres& sp, uint32_t k) {
  __builtin_prefetch(&sp.rec[k]);
  if (sp.order) __builtin_prefetch(&sp.order[k]);
}
RAYCAST_INLINE void prefetch_ahead(const kernel_spheres& sp, const uint32_t* list, size_t x, size_t count) {
  if (list && x + prefetch_distance < count) prefetch_sphere(sp, list[x + prefetch_distance]);
}
RAYCAST_INLINE void prefetch_list(const kernel_spheres& sp, const uint32_t* list, size_t count) {
  const size_t m = count < prefetch_distance ? count : prefetch_distance;
  for (size_t x = 0; x < m; ++x) prefetch_sphere(sp, list[x]);
}

// Tests the spheres list[0 .. count) (0 .. count if list is null) against M ray batches, each step
// for all M before the next. fz_dz: each sphere's f.z d.z where every d.z is the same, or null.
template <int Shades, int M, bool Ortho, bool Deep>
RAYCAST_INLINE void walk(const kernel_spheres& sp, const uint32_t* list, size_t count, rays (&r)[M],
                         closest_hit<Shades> (&h)[M], const float* fz_dz) {
  for (size_t x = 0; x < count; ++x) {
    const size_t k = list ? list[x] : x;
    const sphere_record& e = sp.rec[k];
    prefetch_ahead(sp, list, x, count);
    if constexpr (Deep) {  // a depth-ordered walk: stop where nothing after can be nearer
      bool done = true;
      for (int u = 0; u < M && done; ++u) done = nearer_than<Ortho>(sp, e, r[u], h[u]);
      if (done) return;
    }
    if constexpr (Ortho) {
      for (int u = 0; u < M; ++u) take_nearest_ortho(sp, k, r[u], h[u]);
      continue;
    }
    const vfloat fx = e.fx, fy = e.fy, fz = e.fz;
    vfloat b[M], disc[M];
    vmask can_hit[M];
    bool any_can = false;
    for (int u = 0; u < M; ++u) {
      b[u] = (fx * r[u].d[0] + fy * r[u].d[1]) + (fz_dz ? vfloat(fz_dz[k]) : fz * r[u].d[2]);
      disc[u] = discriminant(e, r[u], fx, fy, fz, b[u]);
      can_hit[u] = disc[u] >= 0.0f;
      any_can = any_can || any(can_hit[u]);
    }
    if (!any_can) continue;  // no lane can hit it: no sqrt, no divide
    for (int u = 0; u < M; ++u) take_nearest(sp, k, r[u], b[u], disc[u], can_hit[u], h[u]);
  }
}

template <int Shades, int M, bool Ortho = false>
RAYCAST_INLINE void intersect(const kernel_spheres& sp, const uint32_t* list, size_t count, rays (&r)[M],
                              closest_hit<Shades> (&h)[M], const float* fz_dz = nullptr) {
  if (sp.depth_key) walk<Shades, M, Ortho, true>(sp, list, count, r, h, fz_dz);
  else walk<Shades, M, Ortho, false>(sp, list, count, r, h, fz_dz);
}

// One ray batch (the one-sample path): the same steps without arrays, which GCC does not keep in
// registers for SSE2's two-half vectors. Deep: a depth-ordered walk, which may stop early.
template <bool Ortho, bool Deep, int Shades>
RAYCAST_INLINE void walk(const kernel_spheres& sp, const uint32_t* list, size_t count, rays& r, closest_hit<Shades>& h) {
  for (size_t x = 0; x < count; ++x) {
    const size_t k = list ? list[x] : x;
    const sphere_record& e = sp.rec[k];
    prefetch_ahead(sp, list, x, count);
    if constexpr (Deep)
      if (nearer_than<Ortho>(sp, e, r, h)) return;  // nothing after can be nearer
    if constexpr (Ortho) {
      take_nearest_ortho(sp, k, r, h);
      continue;
    }
    const vfloat fx = e.fx, fy = e.fy, fz = e.fz;
    const vfloat b = (fx * r.d[0] + fy * r.d[1]) + fz * r.d[2];
    const vfloat disc = discriminant(e, r, fx, fy, fz, b);
    const vmask can_hit = disc >= 0.0f;
    if (none(can_hit)) continue;
    take_nearest(sp, k, r, b, disc, can_hit, h);
  }
}

template <bool Ortho = false, int Shades>
RAYCAST_INLINE void intersect(const kernel_spheres& sp, const uint32_t* list, size_t count, rays& r,
                              closest_hit<Shades>& h) {
  if (sp.depth_key) walk<Ortho, true>(sp, list, count, r, h);
  else walk<Ortho, false>(sp, list, count, r, h);
}

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
