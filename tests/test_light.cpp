// Lit spheres under a directional light with shadows and ambient occlusion
// (scene/light.h, light/README.md): every backend gives the same bytes at
// any thread count and region, the secondary rays' verdicts agree with the
// double reference but for grazing rays, and no hit is shadowed by its own
// sphere at any scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "backend_test.h"
#include "cloud.h"
#include "light/grid.h"
#include "light/key_sort.h"
#include "light/secondary.h"
#include "light/shadow_bins.h"
#include "reference/hittable.h"
#include "simd/cpu.h"
#include "render_support.h"

namespace raycast_test {
namespace {
using namespace raycast;

// A packed box of n lit spheres, w x h, under a light, with shadows and ao rays.
scene lit_box(int64_t n, uint32_t ao, int64_t w = 192, int64_t h = 108) {
  api::scene p = particle_box(n);
  p.cam.width = w;
  p.cam.height = h;
  for (sphere& s : p.spheres) {
    s.shade = shading::lit;
    s.color = color(0.9, 0.7, 0.4);
  }
  p.light.direction = vec3(0.3, 1.0, 0.6);
  p.light.shadows = true;
  p.light.ao_samples = ao;
  p.light.ao_distance = 5 * p.spheres[0].radius;
  return raycast::make_scene(p);
}

image render(const scene& s, backend b, int threads = 1, uint32_t samples = 1) {
  render_options o;
  o.which = b;
  o.threads = threads;
  o.samples = samples;
  return render_with(renderer(s, o), pixel_format::rgb8);
}

class LightBackends : public backend_test<backend> {};

TEST_P(LightBackends, EveryBackendAndThreadCountGivesTheScalarBytes) {
  const scene s = lit_box(3000, 8);
  const image want = render(s, backend::scalar);
  EXPECT_EQ(render(s, GetParam()).bytes, want.bytes);
  EXPECT_EQ(render(s, GetParam(), 2).bytes, want.bytes);
  // The sampled path: ambient occlusion's numbers per sample.
  EXPECT_EQ(render(s, GetParam(), 2, 4).bytes, render(s, backend::scalar, 1, 4).bytes);
}

// A lit cloud (long shadow rays: the renderer asks the light-space bins,
// where the packed box's, its AO cells built, walk those) gives the same
// bytes too.
TEST_P(LightBackends, ACloudsShadowsThroughTheBinsAreTheScalarBytes) {
  api::scene p = particle_cloud(3000);
  p.cam.width = 192;
  p.cam.height = 108;
  for (sphere& sp : p.spheres) sp.shade = shading::lit;
  p.light.direction = vec3(-0.5, 1.0, 0.3);
  p.light.shadows = true;
  scene s = raycast::make_scene(p);
  ASSERT_GT(sphere_grid(s, false).free_path(), sphere_grid::short_free_path);
  const image want = render(s, backend::scalar);
  EXPECT_EQ(render(s, GetParam()).bytes, want.bytes);
  EXPECT_EQ(render(s, GetParam(), 2).bytes, want.bytes);
  s.light.shadows = false;
  EXPECT_NE(render(s, GetParam()).bytes, want.bytes) << "some hits should be in shadow";
}

TEST_P(LightBackends, ARegionIsTheWholeFramesWindow) {
  const scene s = lit_box(3000, 4);
  const image whole = render(s, GetParam());
  render_options o;
  o.which = GetParam();
  const renderer r(s, o);
  image part(whole.width, whole.height, pixel_format::rgb8);
  image_band band = part.band();
  band.row_begin = 30;
  band.row_end = 70;
  band.col_begin = 50;
  band.col_end = 131;
  band.data = part.bytes.data() + 30 * part.stride();
  r.render(band);
  for (int64_t row = 30; row < 70; ++row)
    for (int64_t col = 50; col < 131; ++col)
      for (int k = 0; k < 3; ++k)  // the window's memory starts at its first column
        ASSERT_EQ(part.byte(row, col - 50, k), whole.byte(row, col, k)) << row << "," << col;
}

INSTANTIATE_TEST_SUITE_P(Light, LightBackends, ::testing::ValuesIn(simd_backends), backend_name);

// Without secondary rays the directional light changes nothing but N . L:
// shadows in an empty sky darken nothing; and the headlight without ambient
// occlusion is today's picture, byte for byte.
TEST(Light, ShadowsWithNothingInTheWayAndTheHeadlightChangeNoByte) {
  scene s = lit_box(1, 0);
  const image shadowed = render(s, backend::automatic);
  s.light.shadows = false;
  EXPECT_EQ(render(s, backend::automatic).bytes, shadowed.bytes);
  scene head = lit_box(500, 0);
  head.light = api::light{};
  const image today = render(head, backend::automatic);
  head.light.ao_distance = 1e30;  // ambient occlusion off: the distance means nothing
  EXPECT_EQ(render(head, backend::automatic).bytes, today.bytes);
  EXPECT_EQ(render_with_reference(head, pixel_format::rgb8).bytes.size(), today.bytes.size());
}

// The float renderers' light against the double reference's: bytes within
// one LSB but where a secondary ray's verdict flips (a grazing ray), which
// moves a pixel by one AO ray's share or by the shadow.
TEST(Light, TheFloatPictureIsTheReferencesButForGrazingRays) {
  const scene s = lit_box(2000, 8);
  const image ours = render(s, backend::automatic), ref = render_with_reference(s, pixel_format::rgb8);
  size_t off = 0;
  for (size_t k = 0; k < ours.bytes.size(); ++k) off += std::abs(int(ours.bytes[k]) - int(ref.bytes[k])) > 1;
  EXPECT_LE(double(off), 2e-3 * double(ours.bytes.size())) << off << " bytes differ by more than 1";
}

// How near the segment o + t d, t in [0, tmax], passes to being a different
// verdict for some sphere but skip: min over spheres of | distance of the
// segment from the centre - r | / r.
double grazing(std::span<const sphere> world, const point3& o, const vec3& d, double tmax, const sphere* skip) {
  double g = INFINITY;
  for (const sphere& s : world) {
    if (&s == skip) continue;
    const double t = std::clamp(glm::dot(to_glm(s.center) - o, d), 0.0, tmax);
    const double dist = glm::length(o + t * d - to_glm(s.center));
    g = std::min(g, std::abs(dist - s.radius) / s.radius);
  }
  return g;
}

// Verdict by verdict: the grid's float rays (light/grid.h) against the
// reference's blocked() in double, from the same hit points in the same
// directions, on a box whose spheres touch (packing 0.3 at random: many
// near-contacts).
TEST(Light, GridVerdictsAgreeWithTheReferenceButForGrazingRays) {
  const scene s = lit_box(4000, 0);
  const sphere_grid grid(s);
  const double unit = std::ldexp(1.0, -grid.scale_exp);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  size_t rays = 0, disagree = 0, not_grazing = 0;
  for (uint32_t k = 0; k < s.spheres.size(); ++k) {
    const sphere& sp = s.spheres[k];
    for (int q = 0; q < 16; ++q) {
      const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
      const vec3 d = cosine_direction(n, u(rng), u(rng));
      const double tmax = q % 2 ? INFINITY : 5 * sp.radius;
      const point3 p = to_glm(sp.center) + sp.radius * n;
      const bool want = blocked(s.spheres, p, d, tmax, &sp);
      const float* c = grid.sphere(k);
      const float nf[3] = {float(n.x), float(n.y), float(n.z)}, df[3] = {float(d.x), float(d.y), float(d.z)};
      float pf[3];
      for (int a = 0; a < 3; ++a) pf[a] = c[a] + c[3] * nf[a];
      const bool got = grid.occluded(pf, df, float(tmax * unit), k);
      ++rays;
      if (got == want) continue;
      ++disagree;
      not_grazing += grazing(s.spheres, p, d, tmax, &sp) > 1e-3;
    }
  }
  RecordProperty("secondary_rays", int(rays));
  RecordProperty("disagreeing", int(disagree));
  EXPECT_LE(double(disagree), 1e-4 * double(rays)) << disagree << " of " << rays;
  EXPECT_EQ(not_grazing, 0u) << "verdicts that differ though no sphere is within 1e-3 r of the ray";
}

// Rays through sphere_grid g against testing every sphere with the same
// float test: one ray a sphere, from a point on it (every fifth from beyond
// the grid's box, toward its middle), in a cosine-weighted direction about
// a random normal (every fourth along an axis, the other components +0 or
// -0), a third unbounded, the rest short (or, from outside, just long
// enough to reach the spheres).
// The float test (sphere_grid::blocks) of every sphere but skip.
bool blocked_by_any(const sphere_grid& g, const float o[3], const float d[3], float tmax, uint32_t skip) {
  for (uint32_t q = 0; q < g.size(); ++q)
    if (q != skip && g.blocks(g.position(q), o, d, tmax)) return true;
  return false;
}

// 3000 spheres of mixed sizes at random places, most reaching over their
// cells' faces into others.
scene mixed_sizes() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 3000; ++k)
    p.spheres.push_back(sphere{point3(u(rng) * 4 - 2, u(rng) * 2 - 1, u(rng) * 3 - 8), 0.01 + 0.12 * u(rng) * u(rng)});
  return raycast::make_scene(p);
}

struct walk_count {
  size_t rays = 0, blocked = 0, mismatches = 0;
};
walk_count walk_against_every_sphere(const sphere_grid& g, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  walk_count w;
  for (uint32_t k = 0; k < g.size(); ++k) {
    const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    vec3 d = cosine_direction(n, u(rng), u(rng));
    if (k % 4 == 1) {
      const int a = int(k / 4 % 3);
      d = vec3(k % 8 == 1 ? -0.0 : 0.0, -0.0, 0.0);
      d[a] = n[a] < 0 ? -1.0 : 1.0;
    }
    const float* c = g.sphere(k);
    const bool outside = k % 5 == 0;
    float o[3], df[3];
    for (int a = 0; a < 3; ++a) {
      o[a] = outside ? float(-3 * d[a]) : c[a] + c[3] * float(n[a]);
      df[a] = float(d[a]);
    }
    const float reach = outside ? 3.0f : 0.0f;
    const float tmax = k % 3 == 0 ? INFINITY : reach + float(u(rng) * 0.5);
    const uint32_t skip = outside ? uint32_t(-1) : k;
    const bool want = blocked_by_any(g, o, df, tmax, skip);
    ++w.rays;
    w.blocked += want;
    w.mismatches += g.occluded(o, df, tmax, skip) != want;
  }
  return w;
}

// The grid's walk finds exactly what testing every sphere finds: on spheres
// of mixed sizes at random places (most reaching over their cells' faces
// into others), ...
TEST(Light, GridWalkFindsWhatTestingEverySphereFinds) {
  const sphere_grid g(mixed_sizes());
  ASSERT_GT(g.references(), 2 * g.size()) << "most spheres should reach into other cells";
  const walk_count w = walk_against_every_sphere(g, 6);
  EXPECT_GT(w.blocked, w.rays / 10);
  EXPECT_LT(w.blocked, w.rays * 9 / 10);
  EXPECT_EQ(w.mismatches, 0u) << "of " << w.rays << " rays";
}

// ... on a packed box jittered within lattice cells (its spheres hardly
// reach into other cells) ...
TEST(Light, GridWalkFindsWhatTestingEverySphereFindsInAPackedBox) {
  const sphere_grid g(raycast::make_scene(particle_box(2000)));
  const walk_count w = walk_against_every_sphere(g, 7);
  EXPECT_GT(w.blocked, w.rays / 10);
  EXPECT_EQ(w.mismatches, 0u) << "of " << w.rays << " rays";
}

// ... and on a grid made coarser for a hundred huge spheres among small ones.
scene huge_among_small() {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 1000; ++k)  // small ones over a box, big ones' centres near its middle
    p.spheres.push_back(k % 5 ? sphere{point3(u(rng) * 4 - 2, u(rng) * 3 - 1.5, u(rng) * 3 - 9.5), 0.05}
                              : sphere{point3(u(rng) * 0.5 - 0.25, u(rng) * 0.5 - 0.25, u(rng) * 0.5 - 8.25),
                                       1.2 + 0.1 * u(rng)});
  for (sphere& sp : p.spheres) sp.shade = shading::lit;
  return raycast::make_scene(p);
}

// Small spheres over a box, and as many again in a clump in its middle, a
// few cells across: those cells list hundreds of spheres each, so a walk
// through them tests lists longer than any buffer of its own.
scene clumped() {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  api::scene p;
  for (int k = 0; k < 3000; ++k)
    p.spheres.push_back(k % 2 ? sphere{point3(u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 10), 0.01}
                              : sphere{point3(u(rng) * 0.3 - 0.15, u(rng) * 0.3 - 0.15, u(rng) * 0.3 - 8.15), 0.005});
  return raycast::make_scene(p);
}

TEST(Light, GridWalkFindsWhatTestingEverySphereFindsInACoarseGrid) {
  const sphere_grid g(huge_among_small());
  ASSERT_LT(g.cells() * 4, g.size()) << "the grid should have been made coarser";
  const walk_count w = walk_against_every_sphere(g, 9);
  EXPECT_GT(w.blocked, w.rays / 10);
  EXPECT_LT(w.blocked, w.rays * 19 / 20);
  EXPECT_EQ(w.mismatches, 0u) << "of " << w.rays << " rays";
}

// A hit's rays walked together (sphere_grid::occluded for a group) find,
// ray by ray, what testing every sphere finds: from a point on each sphere,
// eight cosine-weighted directions about a random normal (in every third
// group some along an axis, their other components +0, -0 or below the
// normal floats), most groups short (at most 4 cells: each lane's cells
// tested as it enters them), some longer and every fifth unbounded (each
// lane's cells gathered and tested together), a group of fewer than eight
// now and then; on the grids of the test below (mixed sizes, the lattice
// and random boxes, huge spheres among small ones, clumps). Each verdict is
// also the same ray's walked alone.
struct group_count {
  size_t groups = 0, in_lanes = 0, long_in_lanes = 0, rays = 0, blocked = 0, mismatches = 0, differ_from_lone = 0;
};
group_count groups_against_every_sphere(const sphere_grid& g, uint32_t seed, int lanes) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  group_count w;
  for (uint32_t k = 0; k < g.size(); k += 2) {
    const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
    const float* c = g.sphere(k);
    float o[3], d[sphere_grid::group][3];
    for (int a = 0; a < 3; ++a) o[a] = c[a] + c[3] * float(n[a]);
    const int m = k % 7 == 3 ? 1 + int(k / 7 % 7) : sphere_grid::group;
    for (int l = 0; l < m; ++l) {
      vec3 dl = cosine_direction(n, u(rng), u(rng));
      if (k % 3 == 1 && l % 2 == 0) {
        const int a = (l / 2 + int(k)) % 3;
        dl = vec3(l % 4 ? -0.0 : 0.0, -0.0, 0.0);
        dl[a] = n[a] < 0 ? -1.0 : 1.0;
      }
      for (int a = 0; a < 3; ++a) d[l][a] = float(dl[a]);
      if (k % 3 == 1 && l % 4 == 2)  // along an axis, the others below the normal floats
        for (int a = 0; a < 3; ++a) d[l][a] = std::abs(d[l][a]) == 1.0f ? d[l][a] : a % 2 ? 1e-40f : -3e-41f;
    }
    const bool unbounded = k % 5 == 0;
    const float tmax = unbounded ? std::numeric_limits<float>::infinity() : float(u(rng) * 5) * g.cell_side();
    ++w.groups;
    w.in_lanes += g.walks_in_lanes();
    w.long_in_lanes += g.walks_in_lanes() && tmax > 4 * g.cell_side();
    const uint32_t got = g.occluded(o, d, m, tmax, k, lanes);
    for (int l = 0; l < m; ++l) {
      const bool want = blocked_by_any(g, o, d[l], tmax, k);
      ++w.rays;
      w.blocked += want;
      w.mismatches += ((got >> l) & 1u) != uint32_t(want);
      w.differ_from_lone += ((got >> l) & 1u) != uint32_t(g.occluded(o, d[l], tmax, k));
    }
  }
  return w;
}

TEST(Light, AHitsRaysWalkedTogetherFindWhatTestingEverySphereFinds) {
  // The lattice box lists most spheres in one cell, the random one in several.
  const sphere_grid grids[] = {sphere_grid(mixed_sizes()), sphere_grid(raycast::make_scene(particle_box(2000))),
                               sphere_grid(raycast::make_scene(particle_box_random(2000))), sphere_grid(huge_among_small()),
                               sphere_grid(clumped())};
  ASSERT_GT(grids[2].references(), 4 * grids[2].size()) << "random centres should reach into several cells";
  for (const int lanes : sphere_grid::lane_widths()) {
    for (const sphere_grid& g : grids) {
      SCOPED_TRACE(std::to_string(lanes) + " lanes");
      const group_count w = groups_against_every_sphere(g, 11, lanes);
      EXPECT_EQ(w.mismatches, 0u) << "of " << w.rays << " rays among " << g.size() << " spheres";
      EXPECT_EQ(w.differ_from_lone, 0u) << "verdicts unlike the same ray's walked alone";
      EXPECT_GT(w.in_lanes, w.groups * 7 / 10) << "most groups should walk in lanes";
      EXPECT_GT(w.long_in_lanes, w.groups / 10) << "long groups should walk in lanes too";
      EXPECT_GT(w.blocked, w.rays / 10);
      EXPECT_LT(w.blocked, w.rays * 9 / 10);
    }
  }
}

// The walk in eight lanes is there wherever the CPU runs AVX2 on x86-64 (and
// RAYCAST_MAX_ISA does not cap it below avx2), and taken by default.
TEST(Light, AHitsRaysWalkInTheWidestLanesThisCpuRuns) {
  std::vector<int> want{4};
#if defined(__x86_64__)
  if (cpu().avx2) want.push_back(8);
#endif
  EXPECT_EQ(sphere_grid::lane_widths(), want);
  if (want.back() == 4) GTEST_SKIP() << "no AVX2 here: only the 4-lane walk ran";
}

// The point C + r n of sphere k in the grid's frame (n a unit vector).
void on_sphere(const sphere_grid& g, uint32_t k, const vec3& n, float p[3]) {
  const float* c = g.sphere(k);
  for (int a = 0; a < 3; ++a) p[a] = c[a] + c[3] * float(n[a]);
}

// Shadow rays ask the bins (light/shadow_bins.h) where rays are long and
// walk the grid's cells where they are short; both give every ray the same
// verdict, so the choice changes no byte: from points on the lit sides of
// a packed box's spheres, a cloud's, huge spheres' among small ones (whose
// bins are made coarser), and a column of spheres along the light among
// others (its cells list hundreds, each sorted by reach on its own).
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

TEST(Light, ShadowRaysGetTheSameVerdictsFromTheBinsAndTheCells) {
  const vec3 l = unit_vector(vec3(0.3, 1.0, 0.6));
  const scene box = lit_box(3000, 0), huge = huge_among_small(), column = column_along(l);
  api::scene cp = particle_cloud(3000);
  for (sphere& sp : cp.spheres) sp.shade = shading::lit;
  const scene cloud = raycast::make_scene(cp);
  const float lf[3] = {float(l.x), float(l.y), float(l.z)};
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const scene* s : {&box, &cloud, &huge, &column}) {
    const sphere_grid grid(*s);
    const shadow_bins bins(grid, lf);
    if (s == &column) {
      EXPECT_GT(bins.longest_list(), 300u);
    } else if (s != &huge) {
      EXPECT_EQ(grid.free_path() <= sphere_grid::short_free_path, s == &box) << grid.free_path();
    }
    size_t rays = 0, shadowed = 0, differ = 0;
    for (uint32_t k = 0; k < s->spheres.size(); ++k)
      for (int q = 0; q < 8; ++q) {
        const vec3 n = cosine_direction(l, u(rng), u(rng));
        float pf[3];
        on_sphere(grid, k, n, pf);
        const bool by_bins = bins.occluded(pf, k);
        ++rays;
        shadowed += by_bins;
        differ += by_bins != grid.occluded(pf, lf, INFINITY, k);
      }
    EXPECT_GT(shadowed, rays / 20);
    EXPECT_EQ(differ, 0u) << "of " << rays << " rays";
  }
}

// The grid and the bins are the same built on one thread or several (the
// renderer builds them on its threads for scenes of 2^15 spheres and more).
TEST(Light, GridAndBinsAreTheSameOnAnyNumberOfThreads) {
  const vec3 l = unit_vector(vec3(0.3, 1.0, 0.6));
  const float lf[3] = {float(l.x), float(l.y), float(l.z)};
  api::scene cp = particle_cloud(5000);
  for (sphere& sp : cp.spheres) sp.shade = shading::lit;
  const scene box = lit_box(5000, 0), cloud = raycast::make_scene(cp), column = column_along(l);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const scene* s : {&box, &cloud, &column}) {
    const sphere_grid one(*s, true, 1), three(*s, true, 3);
    ASSERT_EQ(one.size(), three.size());
    EXPECT_EQ(one.cells(), three.cells());
    EXPECT_EQ(one.references(), three.references());
    EXPECT_EQ(one.free_path(), three.free_path());
    size_t differ = 0;
    for (uint32_t k = 0; k < one.size(); ++k)
      differ += one.position(k) != three.position(k) || std::memcmp(one.at(k), three.at(k), 4 * sizeof(float)) != 0;
    EXPECT_EQ(differ, 0u);
    const shadow_bins b1(one, lf, 1), b3(one, lf, 3);
    EXPECT_EQ(b1.bytes(), b3.bytes());
    EXPECT_EQ(b1.longest_list(), b3.longest_list());
    size_t rays = 0, verdicts = 0;
    for (uint32_t k = 0; k < one.size(); ++k)
      for (int q = 0; q < 4; ++q) {
        const vec3 n = cosine_direction(l, u(rng), u(rng));
        float pf[3];
        on_sphere(one, k, n, pf);
        ++rays;
        verdicts += b1.occluded(pf, k) != b3.occluded(pf, k);
        verdicts += one.occluded(pf, lf, 0.05f, k) != three.occluded(pf, lf, 0.05f, k);
      }
    EXPECT_EQ(verdicts, 0u) << "of " << rays << " rays";
  }
}

// The bins' and the grid's builds group records by cell with key_sort: the
// same groups, in the same order within each, as a stable sort by key, over
// one key, keys in few and in many bands, keys no record has, records all
// of one key, and records in runs (parts) filled by as many threads or one.
TEST(Light, KeySortIsAStableSortByKey) {
  std::mt19937 rng(21);
  for (size_t keys : {size_t(1), size_t(7), size_t(5000), size_t(300000)})
    for (size_t n : {size_t(0), size_t(1), size_t(100), size_t(40000), size_t(200000)})
      for (int parts : {1, 3})
        for (bool one_key : {false, true}) {
          std::vector<std::pair<uint32_t, uint32_t>> rec(n);  // key, order given
          for (size_t i = 0; i < n; ++i) rec[i] = {one_key ? uint32_t(keys / 2) : uint32_t(rng() % keys), uint32_t(i)};
          const auto run = [&](int p) { return std::pair(part_begin(n, p, parts), part_begin(n, p + 1, parts)); };
          key_sort<uint32_t> sort(keys, n, parts);
          for (int p = 0; p < parts; ++p)
            for (size_t i = run(p).first; i < run(p).second; ++i) sort.count(p, rec[i].first);
          out_of_order_array<uint32_t> out, first;
          sort.start(out);
#pragma omp parallel for num_threads(parts)
          for (int p = 0; p < parts; ++p)
            for (size_t i = run(p).first; i < run(p).second; ++i) sort.put(p, rec[i].first, rec[i].second);
          size_t seen = 0;
          sort.finish(first, [&](uint32_t* b, uint32_t* e) {
#pragma omp atomic
            seen += size_t(e - b);
          }, parts);
          std::stable_sort(rec.begin(), rec.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
          ASSERT_EQ(first.size(), keys + 1);
          EXPECT_EQ(first[0], 0u);
          EXPECT_EQ(first[keys], n);
          EXPECT_EQ(seen, n);
          size_t bad = 0;
          for (size_t k = 0; k < keys; ++k)
            for (uint32_t j = first[k]; j < first[k + 1]; ++j) bad += rec[j].first != k || rec[j].second != out[j];
          EXPECT_EQ(bad, 0u) << keys << " keys, " << n << " records, " << parts << " parts";
        }
}

// The AO directions' turn about the normal, computed without the C
// library (whose sincosf rounds differently with FMA and without): within
// 1.5e-7 (about a float ulp at 1, 1.19e-7) of the double cos and sin of
// 2 pi u, over the whole turn and at its quarter and eighth points
// (measured: 6.0e-8).
TEST(Light, TheTurnOfAnAoDirectionIsCosAndSinWithinAFloatUlp) {
  std::vector<float> us = {0.0f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f, std::nextafter(1.0f, 0.0f),
                           1e-30f, 0x1p-24f};
  for (int k = 0; k < 200000; ++k) us.push_back(float(k) / 200000.0f + 1.3e-6f * float(k % 7));
  double worst = 0;
  for (float u : us) {
    if (u >= 1.0f) continue;
    float c, s;
    unit_circle(u, c, s);
    const double phi = 2 * 3.14159265358979323846 * double(u);
    worst = std::max({worst, std::abs(c - std::cos(phi)), std::abs(s - std::sin(phi))});
  }
  EXPECT_LE(worst, 1.5e-7);
  float c, s;
  unit_circle(0.25f, c, s);
  EXPECT_EQ(c, 0.0f);
  EXPECT_EQ(s, 1.0f);
}

// A hit's AO numbers are drawn a group of up to 8 rays at a time (Sobol's
// from two points a group: each dimension is linear in its index's bits);
// each ray's are the numbers ao_numbers gives it alone, for every sampler,
// counts that do and do not fill whole groups, and later samples of a pixel
// (random's and stratified's also as their rule in scene/sampler.h says).
// And a hit's 16 Sobol rays are a (0, 4, 2)-net: every box of 1/16 of the
// square with power-of-two sides holds one of them.
// Random's and stratified's numbers as scene/sampler.h states them.
void rule_numbers(const sampling::ao_plan& p, const sampling::ao_seeds& px, uint32_t s, uint32_t k, float& u1,
                  float& u2) {
  const uint32_t r = sampling::mix(px.a + (s * p.count + k + 1) * sampling::golden);
  if (p.kind == sampler_kind::random) {
    u1 = float(r >> 8) * 0x1p-24f;
    u2 = float(sampling::mix(r ^ 0x297a2d39u) >> 8) * 0x1p-24f;
  } else {
    u1 = std::min((float(k % p.nx) + sampling::unit_high<float>(r)) * p.inv_nx, sampling::one_below);
    u2 = std::min((float(k / p.nx) + sampling::unit_low<float>(r)) * p.inv_ny, sampling::one_below);
  }
}

TEST(Light, AoNumbersDrawnAGroupAtATimeAreEachRaysOwn) {
  size_t compared = 0, differ = 0;
  for (sampler_kind kind : {sampler_kind::random, sampler_kind::stratified, sampler_kind::sobol})
    for (uint32_t count : {1u, 3u, 8u, 12u, 16u, 64u}) {
      const sampling::ao_plan plan = sampling::make_ao_plan(kind, count, 42);
      for (uint32_t px = 0; px < 5; ++px) {
        const uint32_t i = px * 977u, j = px * 131u + 7u;
        const sampling::ao_seeds seeds = sampling::ao_pixel(plan, i, j);
        for (uint32_t sample : {0u, 1u, 2u, 5u})
          for (uint32_t k0 = 0; k0 < count; k0 += 8) {
            const uint32_t m = std::min(8u, count - k0);
            float u1[8], u2[8];
            sampling::ao_numbers(plan, seeds, sample, k0, m, u1, u2);
            for (uint32_t q = 0; q < m; ++q) {
              float v1 = 0, v2 = 0;
              sampling::ao_numbers(plan, i, j, sample, k0 + q, v1, v2);
              if (kind != sampler_kind::sobol) rule_numbers(plan, seeds, sample, k0 + q, v1, v2);
              differ += std::memcmp(&v1, &u1[q], 4) != 0 || std::memcmp(&v2, &u2[q], 4) != 0;
              ++compared;
            }
          }
      }
    }
  EXPECT_EQ(differ, 0u) << "of " << compared << " rays";
  const sampling::ao_plan sobol = sampling::make_ao_plan(sampler_kind::sobol, 16, 7);
  for (uint32_t px = 0; px < 20; ++px) {
    float u1[16], u2[16];
    const sampling::ao_seeds seeds = sampling::ao_pixel(sobol, px, 3 * px);
    sampling::ao_numbers(sobol, seeds, 0, 0, 8, u1, u2);
    sampling::ao_numbers(sobol, seeds, 0, 8, 8, u1 + 8, u2 + 8);
    for (int a = 0; a <= 4; ++a) {
      const int cols = 1 << a, rows = 16 >> a;
      std::vector<int> in(16, 0);
      for (int q = 0; q < 16; ++q) ++in[size_t(int(u1[q] * float(cols)) * rows + int(u2[q] * float(rows)))];
      EXPECT_EQ(*std::min_element(in.begin(), in.end()), 1) << "pixel " << px << ", " << cols << " x " << rows;
    }
  }
}

// A hit's AO directions are made four to a vector (light/lanes.h): each
// lane gives ao_direction's bits (the one-at-a-time form, which the Embree
// peer casts), for every count of rays a group holds, normals along and
// near the axes (the frame's sign flips at n.z = 0) and numbers at the
// ends of [0, 1); and each is the double reference's cosine_direction of
// the same numbers to within float rounding.
TEST(Light, AoDirectionsMadeInVectorsAreTheOneAtATimeBits) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), c(-1.0f, 1.0f);
  std::vector<vec3> normals = {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, -1, 0),
                               vec3(1e-7, 0, -1), vec3(0.6, 0.8, 0), vec3(-0.6, 0, 1e-30)};
  for (int k = 0; k < 2000; ++k) normals.push_back(vec3(c(rng), c(rng), c(rng)));
  const float edge[] = {0.0f, 0.25f, 0.5f, std::nextafter(1.0f, 0.0f), 0x1p-24f};
  size_t compared = 0, differ = 0;
  double worst = 0;
  for (size_t q = 0; q < normals.size(); ++q) {
    if (glm::length(normals[q]) < 1e-3) continue;
    const vec3 nd = unit_vector(normals[q]);
    const float n[3] = {float(nd.x), float(nd.y), float(nd.z)};
    const uint32_t m = uint32_t(q % sphere_grid::group) + 1;
    float u1[sphere_grid::group], u2[sphere_grid::group], got[sphere_grid::group][3];
    for (uint32_t a = 0; a < m; ++a) {
      u1[a] = q < 40 ? edge[(q + a) % 5] : u(rng);
      u2[a] = q < 40 ? edge[(q / 5 + a) % 5] : u(rng);
    }
    ao_directions(n, u1, u2, m, got);
    for (uint32_t a = 0; a < m; ++a) {
      float want[3];
      ao_direction(n, u1[a], u2[a], want);
      differ += std::memcmp(want, got[a], sizeof want) != 0;
      ++compared;
      const vec3 ref = cosine_direction(vec3(n[0], n[1], n[2]), u1[a], u2[a]);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(double(got[a][k]) - ref[k]));
    }
  }
  EXPECT_EQ(differ, 0u) << "of " << compared << " directions";
  EXPECT_LE(worst, 2e-6);
}

// The same for shadow rays through the light-space bins (light/shadow_bins.h),
// from points on every sphere's lit side.
TEST(Light, ShadowBinVerdictsAgreeWithTheReferenceButForGrazingRays) {
  const scene s = lit_box(4000, 0);
  const sphere_grid grid(s, false);
  const vec3 l = unit_vector(vec3(0.3, 1.0, 0.6));
  const float lf[3] = {float(l.x), float(l.y), float(l.z)};
  const shadow_bins bins(grid, lf);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  size_t rays = 0, disagree = 0, shadowed = 0, not_grazing = 0;
  for (uint32_t k = 0; k < s.spheres.size(); ++k) {
    const sphere& sp = s.spheres[k];
    for (int q = 0; q < 16; ++q) {
      const vec3 n = cosine_direction(l, u(rng), u(rng));  // a point on the lit side
      const point3 p = to_glm(sp.center) + sp.radius * n;
      const bool want = blocked(s.spheres, p, l, INFINITY, &sp);
      float pf[3];
      on_sphere(grid, k, n, pf);
      const bool got = bins.occluded(pf, k);
      ++rays;
      shadowed += want;
      if (got == want) continue;
      ++disagree;
      not_grazing += grazing(s.spheres, p, l, INFINITY, &sp) > 1e-3;
    }
  }
  RecordProperty("shadow_rays", int(rays));
  RecordProperty("disagreeing", int(disagree));
  EXPECT_GT(shadowed, rays / 10) << "a box's shadow rays are often blocked";
  EXPECT_LE(double(disagree), 1e-4 * double(rays)) << disagree << " of " << rays;
  EXPECT_EQ(not_grazing, 0u);
}

// Touching and overlapping spheres: no light passes between them.
TEST(Light, NoLightPassesBetweenTouchingOrOverlappingSpheres) {
  api::scene p;
  p.spheres = {sphere{point3(0, 0, -5), 1.0}, sphere{point3(2, 0, -5), 1.0}, sphere{point3(0, 1.5, -5), 1.0}};
  const scene s = raycast::make_scene(p);
  const sphere_grid g(s);
  const double unit = std::ldexp(1.0, -g.scale_exp);
  const auto grid_point = [&](const point3& w, float out[3]) {
    for (int a = 0; a < 3; ++a) out[a] = float((w[a] - g.origin[a]) * unit);
  };
  // From sphere 0's point of contact with sphere 1, any ray into sphere 1's side.
  float o[3];
  grid_point(point3(1, 0, -5), o);
  const float along[3] = {0.6f, 0.8f, 0.0f}, grazing_up[3] = {0.001f, 0.9999995f, 0.0f};
  EXPECT_TRUE(g.occluded(o, along, INFINITY, 0));
  EXPECT_TRUE(g.occluded(o, grazing_up, INFINITY, 0));
  // From sphere 0's surface inside sphere 2 (they overlap): blocked whatever the direction.
  grid_point(point3(0, 1, -5), o);
  const float up[3] = {0, 1, 0}, side[3] = {1, 0, 0};
  EXPECT_TRUE(g.occluded(o, up, INFINITY, 0));
  EXPECT_TRUE(g.occluded(o, side, INFINITY, 0));
  // Away from both, open.
  grid_point(point3(-1, 0, -5), o);
  const float left[3] = {-1, 0, 0};
  EXPECT_FALSE(g.occluded(o, left, INFINITY, 0));
}

// No acne: a lit sphere alone casts no shadow on itself and occludes none of
// its own ambient rays, so shadows and AO change no byte of its picture, at
// every scale and up to a light that grazes its surface.
struct stiff_light {
  const char* name;
  double scale;       // the whole scene's
  double radius;      // the sphere's, at distance 5 from the camera
  double far;         // the camera's distance in radii
  vec3 light;
};

class LightStiff : public ::testing::TestWithParam<stiff_light> {};

TEST_P(LightStiff, AHitIsNeverShadowedByItsOwnSphere) {
  const stiff_light& c = GetParam();
  api::scene p;
  p.cam.width = 96;
  p.cam.height = 54;
  p.cam.vfov = 2 * std::atan(1.5 / c.far) * 180 / M_PI;
  const point3 centre(0, 0, -c.far * c.radius * c.scale);  // straight ahead of the camera at the origin
  p.spheres = {sphere{centre, c.radius * c.scale, shading::lit, color(1, 1, 1)}};
  p.light.direction = c.light;
  const scene plain = raycast::make_scene(p);
  p.light.shadows = true;
  p.light.ao_samples = 16;
  const scene shadowed = raycast::make_scene(p);
  for (backend b : {backend::scalar, backend::automatic}) {
    const image want = render(plain, b), got = render(shadowed, b);
    EXPECT_EQ(got.bytes, want.bytes) << to_string(b);
  }
  // Beside a sphere of radius 1e4 (out of view, away from the light), its lit side stays lit.
  p.spheres.push_back(sphere{centre + vec3(-2e4, 0, 0) * c.scale, 1e4 * c.scale, shading::lit, color(1, 1, 1)});
  p.light.ao_samples = 0;
  const scene beside = raycast::make_scene(p);
  p.light.shadows = false;
  EXPECT_EQ(render(beside, backend::automatic).bytes, render(raycast::make_scene(p), backend::automatic).bytes);
}

INSTANTIATE_TEST_SUITE_P(Light, LightStiff,
                         ::testing::Values(stiff_light{"unit", 1.0, 1.0, 5.0, vec3(1, 1, 1)},
                                           stiff_light{"scale_1e6", 1e6, 1.0, 5.0, vec3(1, 1, 1)},
                                           stiff_light{"scale_1em6", 1e-6, 1.0, 5.0, vec3(1, 1, 1)},
                                           stiff_light{"radius_1em4_from_1e3", 1.0, 1e-4, 1e7, vec3(1, 1, 1)},
                                           stiff_light{"radius_1em3_beside_1e4", 1.0, 1e-3, 5.0, vec3(1, 1, 1)},
                                           stiff_light{"grazing_light", 1.0, 1.0, 5.0, vec3(1, 0, 1e-6)}),
                         [](const auto& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace raycast_test
