// A batch's lit lanes: each hit's shadow ray and AO rays, asked of its
// sphere's near-field lists first and of the far field past them
// (light/README.md).
#include "light/secondary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "light/blocks.h"
#include "light/directions.h"
#include "light/frame.h"
#include "scene/sphere.h"

namespace raycast {
namespace {

constexpr uint32_t group = 8;  // a hit's AO rays made and tested together
constexpr uint32_t none = ~0u;
// Hierarchies of more bytes than this (light/far/bvh.h) are walked in turns.
constexpr size_t walk_in_turns_from = size_t(8) << 20;

// One lit lane's hit: its sphere, origin and normal.
struct hit_at {
  uint32_t position;
  sphere4 sphere;       // x y z r, light frame
  float p[3], n[3];     // P = C + r n_out; n facing the ray
  bool inside;
  uint32_t skip() const { return inside ? none : position; }
};

hit_at hit_of(const secondary_rays& r, const lit_lanes& ls, int l) {
  hit_at h;
  h.position = r.bvh->position(ls.sphere[l]);
  h.sphere = r.bvh->at(h.position);
  h.inside = (ls.inside >> l) & 1u;
  for (int c = 0; c < 3; ++c) {
    h.n[c] = ls.n[c][l];
    h.p[c] = h.sphere[c] + h.sphere[3] * (h.inside ? -h.n[c] : h.n[c]);
  }
  return h;
}

// A batch's far-field work: the rays its hits' near lists did not answer,
// each with the lane it counts for (and its ray, for the tests' one-hit
// form), walked once the batch's lanes have been gathered: in turns where
// the hierarchy outgrows the caches (light_kernels::far_occluded_many), so
// that many rays are in flight, else a hit's AO rays from their one origin
// together (far_occluded_one_origin).
struct far_work {
  struct tag {
    uint8_t lane, ray;
    bool shadow;
  };
  std::vector<far_query> q;
  std::vector<tag> of;
  std::vector<uint8_t> blocked;

  void add(const float o[3], const float d[3], float t0, float tmax, uint32_t skip, tag t) {
    q.push_back({{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, t0, tmax, skip});
    of.push_back(t);
  }
  void resolve(const secondary_rays& r) {
    blocked.resize(q.size());
    if (q.empty()) return;
    if (r.far_in_turns) return r.kernels->far_occluded_many(r.view, q.data(), uint32_t(q.size()), blocked.data());
    for (size_t i = 0, j; i < q.size(); i = j) {
      for (j = i + 1; j < q.size() && j - i < group && same_start(q[i], q[j]); ++j) {
      }
      if (j - i == 1) {
        blocked[i] = r.kernels->far_occluded(r.view, q[i].o, q[i].d, q[i].t0, q[i].tmax, q[i].skip);
        continue;
      }
      float d[group][3];
      for (size_t k = i; k < j; ++k)
        for (int c = 0; c < 3; ++c) d[k - i][c] = q[k].d[c];
      const uint32_t b = r.kernels->far_occluded_one_origin(r.view, q[i].o, d, uint32_t(j - i), q[i].t0, q[i].tmax,
                                                            q[i].skip);
      for (size_t k = i; k < j; ++k) blocked[k] = (b >> (k - i)) & 1u;
    }
  }
  // Whether two queries share their origin and segment (a hit's AO rays).
  static bool same_start(const far_query& a, const far_query& b) {
    return a.o[0] == b.o[0] && a.o[1] == b.o[1] && a.o[2] == b.o[2] && a.t0 == b.t0 && a.tmax == b.tmax &&
           a.skip == b.skip;
  }
  void clear() { q.clear(), of.clear(); }
};

// Whether the hit's shadow ray is blocked by its own sphere (seen from
// inside), its shadow list or, in an open scene, the light-space bins;
// where the list was too long to keep, its ray goes to the far field (w)
// and false is returned.
bool shadowed(const secondary_rays& r, const hit_at& h, const near_lists& lists, far_work& w, uint8_t lane,
              const shadow_bins::query* q = nullptr) {
  const float inf = std::numeric_limits<float>::infinity();
  if (h.inside && blocks_one(h.p, r.light, h.sphere.v, inf)) return true;
  if (r.bins) return q ? r.bins->occluded(*q, h.p, h.skip()) : r.bins->occluded(h.p, h.skip());
  if (lists.shadow_whole) return r.kernels->list_blocks(lists.shadow, h.p, r.light, inf);
  w.add(h.p, r.light, 0.0f, inf, h.skip(), {lane, 0, true});
  return false;
}

// Which of a group's m rays are blocked nearby: by the hit's own sphere
// (seen from inside) or its sphere's ball list within the near field's
// reach. The rest that reach past it go to the far field (w), from the
// reach to the AO distance; without a whole list, from the start.
uint32_t blocked_near(const secondary_rays& r, const hit_at& h, const near_lists& lists, const float (*dir)[3],
                      uint32_t m, far_work& w, uint8_t lane, uint32_t ray0) {
  const float reach = r.near->settings().reach, tmax = r.ao_distance;
  uint32_t blocked = 0;
  if (h.inside)
    for (uint32_t a = 0; a < m; ++a) blocked |= uint32_t(blocks_one(h.p, dir[a], h.sphere.v, tmax)) << a;
  float t0 = 0.0f;
  uint32_t skip = h.skip();
  if (lists.ball_whole) {
    blocked |= r.kernels->list_ao(lists.ball, h.p, h.n, dir, int(m), tmax, std::min(tmax, reach));
    if (!(tmax > reach)) return blocked;
    t0 = reach, skip = none;
  }
  for (uint32_t a = 0; a < m; ++a)
    if (!((blocked >> a) & 1u)) w.add(h.p, dir[a], t0, tmax, skip, {lane, uint8_t(ray0 + a), false});
  return blocked;
}

// How many of a hit's AO rays its near lists leave open (their directions
// made a group at a time, four to a vector, before any is tested); the far
// field's verdicts on those that go on are counted once resolved.
uint32_t open_near(const secondary_rays& r, const lit_lanes& ls, int l, const hit_at& h, const near_lists& lists,
                   far_work& w) {
  float t[3], bt[3];
  frame_about(h.n, t, bt);
  const sampling::ao_seeds seeds = sampling::ao_pixel(r.ao, uint32_t(ls.i0 + l), uint32_t(ls.j));
  uint32_t open = 0;
  for (uint32_t a0 = 0; a0 < r.ao.count; a0 += group) {
    const uint32_t m = std::min(group, r.ao.count - a0);
    float u1[group], u2[group], dir[group][3];
    sampling::ao_numbers(r.ao, seeds, ls.sample, a0, m, u1, u2);
    ao_directions_in_frame(h.n, t, bt, u1, u2, m, dir);
    open += m - uint32_t(__builtin_popcount(blocked_near(r, h, lists, dir, m, w, uint8_t(l), 0)));
  }
  return open;
}

hit_at hit_on(const secondary_rays& r, uint32_t k, const float p[3], const float n[3], bool inside) {
  hit_at h;
  h.position = r.bvh->position(k);
  h.sphere = r.bvh->at(h.position);
  h.inside = inside;
  for (int c = 0; c < 3; ++c) h.p[c] = p[c], h.n[c] = n ? n[c] : 0.0f;
  return h;
}

}  // namespace

light_structures::light_structures(const scene& s, const float light[3], const sampling::ao_plan& ao, int threads,
                                   int width, int turns)
    : bvh_(s, threads, ao.count > 0 || !s.light.shadows) {
  rays_.bvh = &bvh_;
  rays_.view = bvh_.view();
  rays_.kernels = &light_kernels_for(width);
  for (int k = 0; k < 3; ++k) rays_.light[k] = light[k];
  rays_.shadows = s.light.shadows;
  rays_.ao = ao;
  rays_.ao_distance = float(std::ldexp(s.light.ao_distance, -bvh_.scale_exp));
  rays_.far_in_turns = turns < 0 ? bvh_.bytes() > walk_in_turns_from : turns > 0;
  const bool open = rays_.shadows && bvh_.free_path() > sphere_bvh::open_free_path;
  if (open) rays_.bins = (bins_ = std::make_unique<shadow_bins>(bvh_, light, threads)).get();
  near_ = std::make_unique<near_field>(
      bvh_, near_settings_for(bvh_, rays_.shadows && !open, light, ao.count > 0, rays_.ao_distance), *rays_.kernels);
  rays_.near = near_.get();
}

uint32_t ao_blocked(const secondary_rays& r, uint32_t k, const float p[3], const float n[3], bool inside,
                    const float (*d)[3], uint32_t m) {
  const hit_at h = hit_on(r, k, p, n, inside);
  far_work w;
  uint32_t blocked = blocked_near(r, h, r.near->of(h.position), d, m, w, 0, 0);
  w.resolve(r);
  for (size_t i = 0; i < w.q.size(); ++i) blocked |= uint32_t(w.blocked[i]) << w.of[i].ray;
  return blocked;
}

bool shadow_blocked(const secondary_rays& r, uint32_t k, const float p[3], bool inside) {
  const hit_at h = hit_on(r, k, p, nullptr, inside);
  far_work w;
  if (shadowed(r, h, r.near->of(h.position), w, 0)) return true;
  w.resolve(r);
  return !w.blocked.empty() && w.blocked[0];
}

namespace {

// The light-space bins' cells of a batch's shadow rays (bit l of `rays`),
// located and read ahead in two steps over the lanes, so that their cache
// misses overlap: each cell's bounds, then its list's far end.
void locate_in_bins(const secondary_rays& r, const hit_at* h, uint32_t rays, shadow_bins::query* q) {
  for (uint32_t b = rays; b != 0; b &= b - 1) {
    const int l = __builtin_ctz(b);
    q[l] = r.bins->locate(h[l].p);
    r.bins->prefetch(q[l], 0);
  }
  for (uint32_t b = rays; b != 0; b &= b - 1) r.bins->prefetch(q[__builtin_ctz(b)], 1);
}

}  // namespace

void light_lanes(const secondary_rays& r, const lit_lanes& ls, float light[lit_lanes::most]) {
  thread_local far_work w;
  w.clear();
  uint32_t open[lit_lanes::most], casts = 0;
  bool shadow[lit_lanes::most];
  hit_at h[lit_lanes::most];
  shadow_bins::query q[lit_lanes::most];
  for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
    const int l = __builtin_ctz(bits);
    h[l] = hit_of(r, ls, l);
    if (r.shadows && ls.diffuse[l] > 0.0f) casts |= 1u << l;
  }
  if (r.bins) locate_in_bins(r, h, casts, q);
  for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
    const int l = __builtin_ctz(bits);
    const bool casts_shadow = (casts >> l) & 1u;
    near_lists lists;
    if ((casts_shadow && !r.bins) || r.ao.count > 0) lists = r.near->of(h[l].position);
    shadow[l] = casts_shadow && shadowed(r, h[l], lists, w, uint8_t(l), &q[l]);
    open[l] = r.ao.count > 0 ? open_near(r, ls, l, h[l], lists, w) : 0;
  }
  w.resolve(r);
  for (size_t i = 0; i < w.q.size(); ++i) {
    if (!w.blocked[i]) continue;
    if (w.of[i].shadow) shadow[w.of[i].lane] = true;
    else --open[w.of[i].lane];
  }
  for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
    const int l = __builtin_ctz(bits);
    const float ambient = r.ao.count > 0 ? float(open[l]) / float(r.ao.count) : 1.0f;
    light[l] = lit_ambient * ambient + (lit_diffuse * ls.diffuse[l]) * (shadow[l] ? 0.0f : 1.0f);
  }
}

}  // namespace raycast
