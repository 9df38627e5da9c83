// A batch's lit lanes: each hit's shadow ray and AO rays, asked of its
// sphere's near-field lists first and of the far field past them
// (light/README.md).
#include "light/secondary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "light/directions.h"
#include "light/frame.h"
#include "scene/sphere.h"

namespace raycast {
namespace {

constexpr uint32_t group = 8;  // a hit's AO rays made and tested together
constexpr uint32_t none = ~0u;

// lanes::blocks for one sphere (x y z r) and one ray: the same float
// operations, so the same verdict (a hit seen from inside asks it of its own
// sphere).
bool blocks_one(const float o[3], const float d[3], const float* s, float tmax) {
  const float ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const float r2 = s[3] * s[3];
  if ((ox * ox + oy * oy) + oz * oz <= r2) return true;
  const float b = (ox * d[0] + oy * d[1]) + oz * d[2];
  if (!(b < 0.0f)) return false;
  const float vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const float m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2, beyond = -b - tmax;
  return m2 <= r2 && (beyond <= 0.0f || beyond * beyond <= gap);
}

// One lit lane's hit: its sphere, origin and normal.
struct hit_at {
  uint32_t position;
  const float* sphere;  // x y z r, light frame
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

bool shadowed(const secondary_rays& r, const hit_at& h, const near_lists& lists) {
  const light_kernels& k = *r.kernels;
  const float inf = std::numeric_limits<float>::infinity();
  if (h.inside && blocks_one(h.p, r.light, h.sphere, inf)) return true;
  if (lists.shadow_whole) return k.list_blocks(lists.shadow, h.p, r.light, inf);
  return k.far_occluded(r.view, h.p, r.light, 0.0f, inf, h.skip());
}

// Which of a group's m rays are blocked: by the hit's own sphere (seen from
// inside), its sphere's ball list within the near field's reach, then the
// far field up to the AO distance; without a whole list, the far field from
// the start.
uint32_t blocked_group(const secondary_rays& r, const hit_at& h, const near_lists& lists, const float (*dir)[3],
                       uint32_t m) {
  const light_kernels& k = *r.kernels;
  const bvh_view& v = r.view;
  const float reach = r.near->settings().reach, tmax = r.ao_distance;
  uint32_t blocked = 0;
  if (h.inside)
    for (uint32_t a = 0; a < m; ++a) blocked |= uint32_t(blocks_one(h.p, dir[a], h.sphere, tmax)) << a;
  if (!lists.ball_whole) {
    for (uint32_t a = 0; a < m; ++a)
      if (!((blocked >> a) & 1u)) blocked |= uint32_t(k.far_occluded(v, h.p, dir[a], 0.0f, tmax, h.skip())) << a;
    return blocked;
  }
  blocked |= k.list_ao(lists.ball, h.p, h.n, dir, int(m), tmax, std::min(tmax, reach));
  if (tmax > reach)
    for (uint32_t a = 0; a < m; ++a)
      if (!((blocked >> a) & 1u)) blocked |= uint32_t(k.far_occluded(v, h.p, dir[a], reach, tmax, none)) << a;
  return blocked;
}

// How many of a hit's AO rays reach their distance: their directions made
// a group at a time, four to a vector, before any is tested.
uint32_t open_ao_rays(const secondary_rays& r, const lit_lanes& ls, int l, const hit_at& h, const near_lists& lists) {
  float t[3], bt[3];
  frame_about(h.n, t, bt);
  const sampling::ao_seeds seeds = sampling::ao_pixel(r.ao, uint32_t(ls.i0 + l), uint32_t(ls.j));
  uint32_t open = 0;
  for (uint32_t a0 = 0; a0 < r.ao.count; a0 += group) {
    const uint32_t m = std::min(group, r.ao.count - a0);
    float u1[group], u2[group], dir[group][3];
    sampling::ao_numbers(r.ao, seeds, ls.sample, a0, m, u1, u2);
    ao_directions_in_frame(h.n, t, bt, u1, u2, m, dir);
    open += m - uint32_t(__builtin_popcount(blocked_group(r, h, lists, dir, m)));
  }
  return open;
}

// One lane: S and A, and the light they make.
float light_lane(const secondary_rays& r, const lit_lanes& ls, int l) {
  const hit_at h = hit_of(r, ls, l);
  const bool casts_shadow = r.shadows && ls.diffuse[l] > 0.0f;
  near_lists lists;
  if (casts_shadow || r.ao.count > 0) lists = r.near->of(h.position);
  const float shadow = casts_shadow && shadowed(r, h, lists) ? 0.0f : 1.0f;
  const float ambient = r.ao.count > 0 ? float(open_ao_rays(r, ls, l, h, lists)) / float(r.ao.count) : 1.0f;
  return lit_ambient * ambient + (lit_diffuse * ls.diffuse[l]) * shadow;
}

}  // namespace

light_structures::light_structures(const scene& s, const float light[3], const sampling::ao_plan& ao, int threads,
                                   int width)
    : bvh_(s, threads) {
  rays_.bvh = &bvh_;
  rays_.view = bvh_.view();
  rays_.kernels = &light_kernels_for(width);
  for (int k = 0; k < 3; ++k) rays_.light[k] = light[k];
  rays_.shadows = s.light.shadows;
  rays_.ao = ao;
  rays_.ao_distance = float(std::ldexp(s.light.ao_distance, -bvh_.scale_exp));
  near_ = std::make_unique<near_field>(
      bvh_, near_settings_for(bvh_, rays_.shadows, light, ao.count > 0, rays_.ao_distance), *rays_.kernels);
  rays_.near = near_.get();
}

uint32_t ao_blocked(const secondary_rays& r, uint32_t k, const float p[3], const float n[3], bool inside,
                    const float (*d)[3], uint32_t m) {
  hit_at h;
  h.position = r.bvh->position(k);
  h.sphere = r.bvh->at(h.position);
  h.inside = inside;
  for (int c = 0; c < 3; ++c) h.p[c] = p[c], h.n[c] = n[c];
  return blocked_group(r, h, r.near->of(h.position), d, m);
}

bool shadow_blocked(const secondary_rays& r, uint32_t k, const float p[3], bool inside) {
  hit_at h;
  h.position = r.bvh->position(k);
  h.sphere = r.bvh->at(h.position);
  h.inside = inside;
  for (int c = 0; c < 3; ++c) h.p[c] = p[c], h.n[c] = 0;
  return shadowed(r, h, r.near->of(h.position));
}

void light_lanes(const secondary_rays& r, const lit_lanes& ls, float light[lit_lanes::most]) {
  for (uint32_t bits = ls.lit; bits != 0; bits &= bits - 1) {
    const int l = __builtin_ctz(bits);
    light[l] = light_lane(r, ls, l);
  }
}

}  // namespace raycast
