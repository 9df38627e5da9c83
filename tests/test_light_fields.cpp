// The light's structures one by one (light/README.md): the far field's
// hierarchy finds exactly what testing every sphere finds, its range queries
// exactly the spheres in range, at every lane width this CPU runs; it is the
// same built on any number of threads; the near field's lists hold what they
// should; the radix sort is stable.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cloud.h"
#include "light/far/bvh.h"
#include "light/far/key_sort.h"
#include "light/far/radix_sort.h"
#include "light/far/shadow_bins.h"
#include "light/kernels.h"
#include "light/near/near_field.h"
#include "reference/hittable.h"
#include "simd/cpu.h"

namespace raycast_test {
namespace {
using namespace raycast;

// The far field's test (light/lanes.h's blocks_beyond) for one sphere and
// one ray, in the same float operations.
bool beyond_ref(const float o[3], const float d[3], const float* s, float t0, float tmax) {
  const float ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
  const float r2 = s[3] * s[3];
  if (t0 <= 0.0f && (ox * ox + oy * oy) + oz * oz <= r2) return true;
  const float b = (ox * d[0] + oy * d[1]) + oz * d[2];
  const float vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
  const float m2 = (vx * vx + vy * vy) + vz * vz, gap = r2 - m2, beyond = -b - tmax, before = t0 + b;
  if (!(m2 <= r2)) return false;
  return (beyond <= 0.0f || beyond * beyond <= gap) && (before <= 0.0f || before * before <= gap);
}

// 3000 spheres of mixed sizes at random places.
scene mixed_sizes() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 3000; ++k)
    p.spheres.push_back(sphere{point3(u(rng) * 4 - 2, u(rng) * 2 - 1, u(rng) * 3 - 8), 0.01 + 0.12 * u(rng) * u(rng)});
  return raycast::make_scene(p);
}
// A hundred huge spheres among small ones.
scene huge_among_small() {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 1000; ++k)
    p.spheres.push_back(k % 5 ? sphere{point3(u(rng) * 4 - 2, u(rng) * 3 - 1.5, u(rng) * 3 - 9.5), 0.05}
                              : sphere{point3(u(rng) * 0.5 - 0.25, u(rng) * 0.5 - 0.25, u(rng) * 0.5 - 8.25),
                                       1.2 + 0.1 * u(rng)});
  return raycast::make_scene(p);
}
// Small spheres over a box, and as many again in a clump a few radii wide
// in its middle (whose spheres' lists are too long to keep), and a few
// hundred at one point (one Morton code: leaves cut from equal codes).
scene clumped() {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 3000; ++k)
    p.spheres.push_back(k % 2 ? sphere{point3(u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 10), 0.01}
                              : sphere{point3(u(rng) * 0.3 - 0.15, u(rng) * 0.3 - 0.15, u(rng) * 0.3 - 8.15), 0.005});
  for (int k = 0; k < 300; ++k) p.spheres.push_back(sphere{point3(1.0, 1.0, -9.0), 0.001 * (1 + k % 3)});
  return raycast::make_scene(p);
}

std::vector<scene> scenes() {
  std::vector<scene> all;
  all.push_back(mixed_sizes());
  all.push_back(raycast::make_scene(particle_box(2000)));
  all.push_back(raycast::make_scene(particle_box_random(2000)));
  all.push_back(raycast::make_scene(particle_cloud(3000)));
  all.push_back(huge_among_small());
  all.push_back(clumped());
  return all;
}

struct far_count {
  size_t rays = 0, blocked = 0, mismatches = 0;
};

// Rays through the far field against testing every sphere: from a point on
// each sphere (every fifth from beyond the spheres' box, toward its middle),
// in a cosine-weighted direction about a random normal (every fourth along
// an axis, the other components +0, -0 or below the normal floats), from
// t0 = 0 or a few radii on, to infinity or a short way.
far_count far_against_every_sphere(const sphere_bvh& b, const light_kernels& k, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const bvh_view v = b.view();
  far_count w;
  for (uint32_t q = 0; q < b.size(); ++q) {
    const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    vec3 d = cosine_direction(n, u(rng), u(rng));
    float df[3];
    for (int a = 0; a < 3; ++a) df[a] = float(d[a]);
    if (q % 4 == 1) {
      const int a = int(q / 4 % 3);
      for (int c = 0; c < 3; ++c) df[c] = c == a ? (n[a] < 0 ? -1.0f : 1.0f) : q % 8 == 1 ? -0.0f : q % 16 == 5 ? 1e-40f : 0.0f;
    }
    const uint32_t p = b.position(q);
    const sphere4 c = b.at(p);
    const bool outside = q % 5 == 0;
    float o[3];
    for (int a = 0; a < 3; ++a) o[a] = outside ? -3.0f * df[a] : c[a] + c[3] * float(n[a]);
    const float t0 = outside || q % 3 != 1 ? 0.0f : c[3] * float(1 + q % 7);
    const float tmax = q % 3 == 0 ? INFINITY : (outside ? 3.0f : t0) + float(u(rng) * 0.5);
    const uint32_t skip = outside ? ~0u : p;
    bool want = false;
    for (uint32_t j = 0; j < b.size() && !want; ++j) want = j != skip && beyond_ref(o, df, b.at(j).v, t0, tmax);
    ++w.rays;
    w.blocked += want;
    w.mismatches += k.far_occluded(v, o, df, t0, tmax, skip) != want;
  }
  return w;
}

TEST(LightFields, TheFarFieldFindsWhatTestingEverySphereFinds) {
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    ASSERT_EQ(b.size(), s.spheres.size());
    ASSERT_GT(b.nodes(), 0u);
    for (const int width : light_widths()) {
      SCOPED_TRACE(std::to_string(width) + " lanes, " + std::to_string(b.size()) + " spheres");
      const far_count w = far_against_every_sphere(b, light_kernels_for(width), 6);
      EXPECT_EQ(w.mismatches, 0u) << "of " << w.rays << " rays";
      EXPECT_GT(w.blocked, w.rays / 20);
      EXPECT_LT(w.blocked, w.rays * 19 / 20);
    }
  }
}

// Many rays walked in turns get the verdicts of each walked alone: rays of
// far_against_every_sphere's kinds, some with nothing to walk (t0 > tmax).
TEST(LightFields, RaysWalkedInTurnsGetTheVerdictsOfEachAlone) {
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    const bvh_view v = b.view();
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<far_query> q;
    for (uint32_t k = 0; k < b.size(); ++k) {
      const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5)), d = cosine_direction(n, u(rng), u(rng));
      const uint32_t p = b.position(k);
      const sphere4 c = b.at(p);
      far_query f;
      for (int a = 0; a < 3; ++a) f.o[a] = c[a] + c[3] * float(n[a]), f.d[a] = float(d[a]);
      f.t0 = k % 3 == 0 ? 0.0f : c[3] * float(k % 5);
      f.tmax = k % 4 == 0 ? INFINITY : k % 7 == 0 ? f.t0 / 2 : c[3] * 20;
      f.skip = k % 3 == 0 ? p : ~0u;
      q.push_back(f);
    }
    for (const int width : light_widths()) {
      const light_kernels& k = light_kernels_for(width);
      std::vector<uint8_t> got(q.size(), 9);
      k.far_occluded_many(v, q.data(), uint32_t(q.size()), got.data());
      size_t differ = 0, blocked = 0;
      for (size_t i = 0; i < q.size(); ++i) {
        const bool want = k.far_occluded(v, q[i].o, q[i].d, q[i].t0, q[i].tmax, q[i].skip);
        differ += got[i] != uint8_t(want);
        blocked += want;
      }
      EXPECT_EQ(differ, 0u) << width << " lanes, " << q.size() << " rays";
      EXPECT_GT(blocked, q.size() / 20);
      EXPECT_LT(blocked, q.size() * 19 / 20);
    }
  }
}

// A hit's rays walked together from one origin get what testing every
// sphere finds: one to eight rays from a point on every eighth sphere
// (some along an axis), past t0 = 0 or a few radii, to infinity or a short
// way, their own sphere skipped or not.
TEST(LightFields, RaysFromOneOriginGetWhatTestingEverySphereFinds) {
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    const bvh_view v = b.view();
    for (const int width : light_widths()) {
      const light_kernels& k = light_kernels_for(width);
      std::mt19937 rng(23);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      size_t rays = 0, blocked = 0, differ = 0;
      for (uint32_t q = 0; q < b.size(); q += 8) {
        const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
        const uint32_t p = b.position(q), m = q / 8 % 8 + 1;
        const sphere4 c = b.at(p);
        float o[3], d[8][3];
        for (int a = 0; a < 3; ++a) o[a] = c[a] + c[3] * float(n[a]);
        for (uint32_t r = 0; r < m; ++r) {
          const vec3 dr = cosine_direction(n, u(rng), u(rng));
          for (int a = 0; a < 3; ++a) d[r][a] = r == 3 ? (a == int(q % 3) ? (n[a] < 0 ? -1.0f : 1.0f) : 0.0f) : float(dr[a]);
        }
        const float t0 = q % 3 == 1 ? c[3] * float(1 + q % 5) : 0.0f;
        const float tmax = q % 4 == 0 ? INFINITY : t0 + c[3] * 20;
        const uint32_t skip = q % 7 == 0 ? ~0u : p;
        const uint32_t got = k.far_occluded_one_origin(v, o, d, m, t0, tmax, skip);
        for (uint32_t r = 0; r < m; ++r) {
          bool want = false;
          for (uint32_t j = 0; j < b.size() && !want; ++j) want = j != skip && beyond_ref(o, d[r], b.at(j).v, t0, tmax);
          ++rays;
          blocked += want;
          differ += ((got >> r) & 1u) != uint32_t(want);
        }
        EXPECT_EQ(got >> m, 0u);
      }
      EXPECT_EQ(differ, 0u) << width << " lanes, " << rays << " rays";
      EXPECT_GT(blocked, rays / 20);
      EXPECT_LT(blocked, rays * 19 / 20);
    }
  }
}

// Every sphere is in one leaf, once, and leaves hold at most eight.
TEST(LightFields, EverySphereIsInOneLeaf) {
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    const bvh_view v = b.view();
    std::vector<int> seen(b.size(), 0);
    size_t leaves = 0;
    const auto leaf = [&](uint32_t ref) {
      ++leaves;
      EXPECT_LE(bvh_ref::count(ref), bvh_ref::most_in_leaf);
      for (uint32_t p = bvh_ref::first(ref); p < bvh_ref::first(ref) + bvh_ref::count(ref); ++p) ++seen[p];
    };
    if (bvh_ref::is_leaf(v.root)) leaf(v.root);
    for (size_t i = 0; i < b.nodes(); ++i)
      for (uint32_t c : v.nodes[i].child)
        if (c != bvh_ref::empty && bvh_ref::is_leaf(c)) leaf(c);
    EXPECT_EQ(leaves, b.leaves());
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), ptrdiff_t(b.size()));
    for (uint32_t k = 0; k < b.size(); ++k) {
      const sphere sp = s.sphere_at(k);
      const sphere4 c = b.sphere(k);
      const double unit = std::ldexp(1.0, -b.scale_exp);
      EXPECT_EQ(c[3], float(sp.radius * unit));
      EXPECT_EQ(c[0], float((sp.center.x - b.origin[0]) * unit));
    }
  }
}

// The range queries the near field gathers with: exactly the spheres in
// range (the same float test as brute force; compared by their x, y, z, r),
// at every lane width.
using coords = std::array<float, 4>;
std::vector<coords> sorted_rows(float* const rows[4], uint32_t n) {
  std::vector<coords> v(n);
  for (uint32_t i = 0; i < n; ++i) v[i] = {rows[0][i], rows[1][i], rows[2][i], rows[3][i]};
  std::sort(v.begin(), v.end());
  return v;
}

TEST(LightFields, RangeQueriesFindExactlyTheSpheresInRange) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    const bvh_view v = b.view();
    const vec3 ld = unit_vector(vec3(0.3, 1.0, 0.6));
    const float l[3] = {float(ld.x), float(ld.y), float(ld.z)};
    const uint32_t room = uint32_t(b.size()) + 8;
    std::vector<float> storage(4 * size_t(room)), along(room);
    float* const rows[4] = {&storage[0], &storage[room], &storage[2 * size_t(room)], &storage[3 * size_t(room)]};
    for (const int width : light_widths()) {
      SCOPED_TRACE(std::to_string(width) + " lanes, " + std::to_string(b.size()) + " spheres");
      const light_kernels& k = light_kernels_for(width);
      size_t differ = 0, found = 0, alongs = 0;
      for (uint32_t p = 0; p < b.size(); p += 7) {
        const sphere4 c = b.at(p);
        const float reach = c[3] * float(1 + 8 * u(rng)), slack = 1e-6f;
        std::vector<coords> want, want_capsule;
        for (uint32_t j = 0; j < b.size(); ++j) {
          if (j == p) continue;
          const sphere4 t = b.at(j);
          const float dx = t[0] - c[0], dy = t[1] - c[1], dz = t[2] - c[2], lim = reach + t[3];
          if ((dx * dx + dy * dy) + dz * dz <= lim * lim) want.push_back({t[0], t[1], t[2], t[3]});
          const float a = (dx * l[0] + dy * l[1]) + dz * l[2];
          const float px = dx - a * l[0], py = dy - a * l[1], pz = dz - a * l[2], cl = (c[3] + t[3]) + slack;
          if ((px * px + py * py) + pz * pz <= cl * cl && a >= -(t[3] + slack)) want_capsule.push_back({t[0], t[1], t[2], t[3]});
        }
        std::sort(want.begin(), want.end());
        std::sort(want_capsule.begin(), want_capsule.end());
        const uint32_t n = k.gather_ball(v, c.v, reach, p, rows, uint32_t(b.size()));
        differ += sorted_rows(rows, n) != want;
        const uint32_t m = k.gather_capsule(v, c.v, c[3], l, slack, p, rows, along.data(), uint32_t(b.size()));
        differ += sorted_rows(rows, m) != want_capsule;
        for (uint32_t i = 0; i < m; ++i)  // each one's distance along the light
          alongs += along[i] != ((rows[0][i] - c[0]) * l[0] + (rows[1][i] - c[1]) * l[1]) + (rows[2][i] - c[2]) * l[2];
        found += want.size() + want_capsule.size();
        if (want.size() > 2) {  // a cap: one more than it, once more are found
          EXPECT_EQ(k.gather_ball(v, c.v, reach, p, rows, 2), 3u);
        }
      }
      EXPECT_EQ(differ, 0u);
      EXPECT_EQ(alongs, 0u);
      EXPECT_GT(found, b.size() / 7);
    }
  }
}

// The hierarchy is the same built on one thread or several (the renderer
// builds it on its threads for scenes of 2^15 spheres and more): the same
// positions, nodes and density, bit for bit.
TEST(LightFields, TheFarFieldIsTheSameOnAnyNumberOfThreads) {
  const scene big = raycast::make_scene(particle_box_random(100000));
  for (const scene* s : {&big}) {
    const sphere_bvh one(*s, 1), three(*s, 3);
    ASSERT_EQ(one.size(), three.size());
    ASSERT_EQ(one.nodes(), three.nodes());
    EXPECT_EQ(one.leaves(), three.leaves());
    EXPECT_EQ(one.density(), three.density());
    size_t differ = 0;
    for (uint32_t k = 0; k < one.size(); ++k) differ += one.position(k) != three.position(k);
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(std::memcmp(one.view().nodes, three.view().nodes, one.nodes() * sizeof(bvh_node)), 0);
    EXPECT_EQ(std::memcmp(one.view().leaf, three.view().leaf, one.size() * 16), 0);
  }
}

// The near field's lists: a sphere's ball list is the spheres within reach
// of it, nearest shells first; its shadow list those along the light, in
// order along it; asked again, the same record, gathered once; too long a
// list is not kept.
TEST(LightFields, TheNearFieldsListsHoldTheSpheresInReach) {
  for (const scene& s : scenes()) {
    const sphere_bvh b(s);
    const vec3 ld = unit_vector(vec3(0.3, 1.0, 0.6));
    const float l[3] = {float(ld.x), float(ld.y), float(ld.z)};
    const near_settings set = near_settings_for(b, true, l, true, INFINITY);
    ASSERT_GT(set.reach, 0.0f);
    const near_field near(b, set, light_kernels_for());
    size_t whole = 0, cut = 0, listed = 0;
    for (uint32_t p = 0; p < b.size(); p += 11) {
      const size_t before = near.lists();
      const near_lists a = near.of(p), again = near.of(p);  // kept: the same record, gathered once
      EXPECT_EQ(a.ball.blocks, again.ball.blocks);
      EXPECT_EQ(near.lists(), before + 1);
      const sphere4 c = b.at(p);
      size_t want = 0;
      for (uint32_t j = 0; j < b.size(); ++j) {
        const sphere4 t = b.at(j);
        const float dx = t[0] - c[0], dy = t[1] - c[1], dz = t[2] - c[2];
        want += j != p && std::sqrt((dx * dx + dy * dy) + dz * dz) <= c[3] + set.reach + t[3];
      }
      if (!a.ball_whole) {
        EXPECT_GT(want, near_field::most_listed / 2);
        ++cut;
        continue;
      }
      ++whole;
      EXPECT_GE(a.ball.count, want);  // its reach and a 2^-12 more
      EXPECT_LE(a.ball.count, want + want / 8 + 2);
      listed += a.ball.count;
      float last = -INFINITY;
      for (uint32_t i = 0; i < a.shadow.count; ++i) {  // in order along the light
        const float* blk = a.shadow.blocks + (i / 16) * 64 + i % 16;
        const float along = ((blk[0] - c[0]) * l[0] + (blk[16] - c[1]) * l[1]) + (blk[32] - c[2]) * l[2];
        EXPECT_GE(along, last);
        last = along;
      }
    }
    EXPECT_GT(whole, 0u);
    EXPECT_GT(listed, 0u);
    EXPECT_EQ(near.lists(), whole + cut);
  }
}

// Shadow rays get the same verdicts from the light-space bins (open
// scenes' shadow rays) and from their spheres' shadow lists (packed ones'):
// from points on the lit sides of a packed box's spheres, a cloud's, huge
// spheres' among small ones, and a column of spheres along the light among
// others (its cells list hundreds, each sorted by reach on its own); and the
// bins are the same built on one thread or three.
scene column_along(const vec3& l) {
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 1000; ++k) {
    const point3 c = k % 5 < 2 ? point3(u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 2)
                               : point3(0.02 * u(rng), 0.02 * u(rng), 0.02 * u(rng)) + (u(rng) * 8 - 4) * l;
    p.spheres.push_back(sphere{c, 0.01 + 0.02 * u(rng)});
  }
  for (sphere& sp : p.spheres) sp.shade = shading::lit;
  return raycast::make_scene(p);
}

TEST(LightFields, ShadowRaysGetTheSameVerdictsFromTheBinsAndTheShadowLists) {
  const vec3 ld = unit_vector(vec3(0.3, 1.0, 0.6));
  const float l[3] = {float(ld.x), float(ld.y), float(ld.z)};
  std::vector<scene> all = scenes();
  all.push_back(column_along(ld));
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const scene& s : all) {
    const sphere_bvh b(s);
    const shadow_bins bins(b, l), three(b, l, 3);
    EXPECT_EQ(bins.bytes(), three.bytes());
    EXPECT_EQ(bins.longest_list(), three.longest_list());
    if (&s == &all.back()) {
      EXPECT_GT(bins.longest_list(), 300u);
    }
    near_settings set;
    set.shadows = true;
    for (int a = 0; a < 3; ++a) set.light[a] = l[a];
    for (const int width : light_widths()) {
      const light_kernels& k = light_kernels_for(width);
      const near_field near(b, set, k);
      size_t rays = 0, shadowed = 0, differ = 0;
      for (uint32_t p = 0; p < b.size(); p += 3) {
        const sphere4 c = b.at(p);
        const vec3 n = cosine_direction(ld, u(rng), u(rng));
        float o[3];
        for (int a = 0; a < 3; ++a) o[a] = c[a] + c[3] * float(n[a]);
        const near_lists lists = near.of(p);
        ASSERT_TRUE(lists.shadow_whole);
        const bool by_bins = bins.occluded(o, p);
        ++rays;
        shadowed += by_bins;
        differ += by_bins != k.list_blocks(lists.shadow, o, l, INFINITY);
        differ += by_bins != three.occluded(o, p);
      }
      EXPECT_GT(shadowed, rays / 20);
      EXPECT_EQ(differ, 0u) << width << " lanes, of " << rays << " rays among " << b.size() << " spheres";
    }
  }
}

// The bins' build groups their entries by cell with key_sort: the same
// groups, in the same order within each, as a stable sort by key of every
// (record, key) pair, over one key, keys in few and in many bands, keys no
// record has, records all of one key, records of one key and of several
// (some a band apart: a disc over two rows of cells), and records in runs
// (parts) filled by as many threads or one.
TEST(LightFields, KeySortIsAStableSortByKey) {
  std::mt19937 rng(21);
  struct rec {
    uint32_t key, order, many, stride;  // keys: key + j stride for j < many, below the count
  };
  for (size_t keys : {size_t(1), size_t(7), size_t(5000), size_t(300000)})
    for (size_t n : {size_t(0), size_t(1), size_t(100), size_t(40000), size_t(200000)})
      for (int parts : {1, 3})
        for (bool one_key : {false, true}) {
          std::vector<rec> in(n);
          for (size_t i = 0; i < n; ++i)
            in[i] = {one_key ? uint32_t(keys / 2) : uint32_t(rng() % keys), uint32_t(i),
                     one_key ? 1u : 1u + uint32_t(rng() % 4), 1u + uint32_t(rng() % 2) * uint32_t(rng() % 3000)};
          const auto keys_of = [keys](const rec& r, auto&& f) {
            for (uint32_t j = 0; j < r.many && r.key + size_t(j) * r.stride < keys; ++j) f(r.key + size_t(j) * r.stride);
          };
          std::vector<std::pair<uint32_t, uint32_t>> pairs;  // key, order given
          for (const rec& r : in) keys_of(r, [&](size_t k) { pairs.emplace_back(uint32_t(k), r.order); });
          const auto run = [&](int p) { return std::pair(part_begin(n, p, parts), part_begin(n, p + 1, parts)); };
          key_sort<rec, decltype(keys_of)> sort(keys, pairs.size(), parts, keys_of);
          size_t counted = 0;
          for (int p = 0; p < parts; ++p)
            for (size_t i = run(p).first; i < run(p).second; ++i) counted += sort.count(p, in[i]);
          EXPECT_EQ(counted, pairs.size());
          out_of_order_array<rec> out;
          out_of_order_array<uint32_t> first;
          sort.start(out);
#pragma omp parallel for num_threads(parts)
          for (int p = 0; p < parts; ++p)
            for (size_t i = run(p).first; i < run(p).second; ++i) sort.put(p, in[i]);
          size_t seen = 0;
          sort.finish(first, [&](rec* b, rec* e) {
#pragma omp atomic
            seen += size_t(e - b);
          }, parts);
          std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
          ASSERT_EQ(first.size(), keys + 1);
          EXPECT_EQ(first[0], 0u);
          EXPECT_EQ(first[keys], pairs.size());
          EXPECT_EQ(seen, pairs.size());
          size_t bad = 0;
          for (size_t k = 0; k < keys; ++k)
            for (uint32_t j = first[k]; j < first[k + 1]; ++j) bad += pairs[j].first != k || pairs[j].second != out[j].order;
          EXPECT_EQ(bad, 0u) << keys << " keys, " << n << " records, " << parts << " parts";
        }
}

// The radix sort orders by the chosen bits and keeps the order of equal
// ones, on one part or several.
TEST(LightFields, RadixSortIsStableByItsBits) {
  std::mt19937_64 rng(21);
  for (size_t n : {size_t(0), size_t(1), size_t(100), size_t(40000)})
    for (int parts : {1, 3})
      for (uint64_t spread : {uint64_t(1), uint64_t(5), uint64_t(1) << 30}) {
        out_of_order_array<uint64_t> keys;
        keys.resize(n);
        for (size_t i = 0; i < n; ++i) keys[i] = (rng() % spread) << 32 | i;
        std::vector<uint64_t> want(keys.begin(), keys.end());
        std::stable_sort(want.begin(), want.end(), [](uint64_t a, uint64_t b) { return a >> 32 < b >> 32; });
        radix_sort(keys, 32, 30, parts);
        EXPECT_TRUE(std::equal(want.begin(), want.end(), keys.begin())) << n << " keys, " << parts << " parts";
      }
}

// The widths this CPU runs: four everywhere; on x86-64 eight with AVX2 and
// sixteen with AVX-512 (RAYCAST_MAX_ISA below them leaves them out).
TEST(LightFields, TheKernelsComeInTheWidthsThisCpuRuns) {
  std::vector<int> want{4};
#if defined(__x86_64__)
  if (cpu().avx2) want.push_back(8);
  if (cpu().avx512) want.push_back(16);
#endif
  EXPECT_EQ(light_widths(), want);
  for (int w : want) EXPECT_EQ(light_kernels_for(w).width, w);
  EXPECT_EQ(light_kernels_for().width, want.back());
  if (want.back() < 16) GTEST_SKIP() << "the widest lanes here are " << want.back() << ": the others did not run";
}

}  // namespace
}  // namespace raycast_test
