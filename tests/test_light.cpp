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
#include "light/kernels.h"
#include "light/secondary.h"
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

// A lit cloud (long shadow rays, each sphere's shadow list through the
// whole cloud) gives the same bytes too.
TEST_P(LightBackends, ACloudsShadowsAreTheScalarBytes) {
  api::scene p = particle_cloud(3000);
  p.cam.width = 192;
  p.cam.height = 108;
  for (sphere& sp : p.spheres) sp.shade = shading::lit;
  p.light.direction = vec3(-0.5, 1.0, 0.3);
  p.light.shadows = true;
  scene s = raycast::make_scene(p);
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

// The structures of a lit box's rays (light/secondary.h), with the light and
// its AO plan, at the given width.
light_structures structures_of(const scene& s, int width = 0, int turns = -1) {
  const vec3 l = unit_vector(to_glm(s.light.direction.value_or(api::vec3{0.3, 1.0, 0.6})));
  const float lf[3] = {float(l.x), float(l.y), float(l.z)};
  return light_structures(s, lf, sampling::make_ao_plan(default_sampler, s.light.ao_samples, 0), 1, width, turns);
}

// Sphere k's point C + r n in the light's frame (n a unit vector).
void on_sphere(const sphere_bvh& b, uint32_t k, const vec3& n, float p[3]) {
  const sphere4 c = b.sphere(k);
  for (int a = 0; a < 3; ++a) p[a] = c[a] + c[3] * float(n[a]);
}

// Verdict by verdict: a hit's AO rays as the renderer casts them (its
// sphere's near list, the far field past it) against the reference's
// blocked() in double, from the same hit points in the same directions, on
// a box whose spheres touch (packing 0.3 at random: many near-contacts),
// at every lane width, bounded and unbounded (its far rays walked one at a
// time and in turns).
TEST(Light, AoVerdictsAgreeWithTheReferenceButForGrazingRays) {
  for (const int width : light_widths()) {
    SCOPED_TRACE(std::to_string(width) + " lanes");
    for (const int turns : {-1, 0, 1}) {
      const bool unbounded = turns >= 0;
      scene s = lit_box(4000, 8);
      if (unbounded) s.light.ao_distance = INFINITY;
      const light_structures ls = structures_of(s, width, turns);
      const sphere_bvh& b = ls.bvh();
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      size_t rays = 0, disagree = 0, not_grazing = 0, blocked_rays = 0;
      for (uint32_t k = 0; k < s.spheres.size(); ++k) {
        const sphere& sp = s.spheres[k];
        const vec3 n = unit_vector(vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
        const float nf[3] = {float(n.x), float(n.y), float(n.z)};
        float pf[3], d[8][3];
        on_sphere(b, k, n, pf);
        vec3 dd[8];
        for (int q = 0; q < 8; ++q) {
          dd[q] = cosine_direction(n, u(rng), u(rng));
          for (int a = 0; a < 3; ++a) d[q][a] = float(dd[q][a]);
        }
        const uint32_t got = ao_blocked(ls.rays(), k, pf, nf, false, d, 8);
        for (int q = 0; q < 8; ++q) {
          const point3 p = to_glm(sp.center) + sp.radius * n;
          const bool want = blocked(s.spheres, p, dd[q], s.light.ao_distance, &sp);
          ++rays;
          blocked_rays += want;
          if (((got >> q) & 1u) == uint32_t(want)) continue;
          ++disagree;
          not_grazing += grazing(s.spheres, p, dd[q], s.light.ao_distance, &sp) > 1e-3;
        }
      }
      RecordProperty("ao_rays", int(rays));
      RecordProperty("disagreeing", int(disagree));
      EXPECT_GT(blocked_rays, rays / 10);
      EXPECT_LT(blocked_rays, rays * 9 / 10);
      EXPECT_LE(double(disagree), 1e-4 * double(rays)) << disagree << " of " << rays;
      EXPECT_EQ(not_grazing, 0u) << "verdicts that differ though no sphere is within 1e-3 r of the ray";
    }
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
// (random's and stratified's also as their rule in sampling/sampler.h says).
// And a hit's 16 Sobol rays are a (0, 4, 2)-net: every box of 1/16 of the
// square with power-of-two sides holds one of them.
// Random's and stratified's numbers as sampling/sampler.h states them.
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
    const uint32_t m = uint32_t(q % 8) + 1;
    float u1[8], u2[8], got[8][3];
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

// The same for shadow rays, from points on every sphere's lit side, at every
// lane width: a packed box's (its spheres' shadow lists) and a cloud's (an
// open scene: light-space bins, and no nodes in the far field).
TEST(Light, ShadowVerdictsAgreeWithTheReferenceButForGrazingRays) {
  api::scene cp = particle_cloud(4000);
  for (sphere& sp : cp.spheres) sp.shade = shading::lit;
  cp.light.direction = vec3(0.3, 1.0, 0.6);
  cp.light.shadows = true;
  const scene box = lit_box(4000, 0), cloud = raycast::make_scene(cp);
  const vec3 l = unit_vector(vec3(0.3, 1.0, 0.6));
  for (const int width : light_widths())
    for (const scene* s : {&box, &cloud}) {
      SCOPED_TRACE(std::to_string(width) + " lanes, " + (s == &box ? "box" : "cloud"));
      const light_structures ls = structures_of(*s, width);
      EXPECT_EQ(ls.rays().bins != nullptr, s == &cloud);
      EXPECT_EQ(ls.bvh().has_nodes(), s == &box);
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      size_t rays = 0, disagree = 0, shadowed = 0, not_grazing = 0;
      for (uint32_t k = 0; k < s->spheres.size(); ++k) {
        const sphere& sp = s->spheres[k];
        for (int q = 0; q < 4; ++q) {
          const vec3 n = cosine_direction(l, u(rng), u(rng));  // a point on the lit side
          const point3 p = to_glm(sp.center) + sp.radius * n;
          const bool want = blocked(s->spheres, p, l, INFINITY, &sp);
          float pf[3];
          on_sphere(ls.bvh(), k, n, pf);
          const bool got = shadow_blocked(ls.rays(), k, pf, false);
          ++rays;
          shadowed += want;
          if (got == want) continue;
          ++disagree;
          not_grazing += grazing(s->spheres, p, l, INFINITY, &sp) > 1e-3;
        }
      }
      RecordProperty("shadow_rays", int(rays));
      RecordProperty("disagreeing", int(disagree));
      EXPECT_GT(shadowed, rays / 20) << "some shadow rays are blocked";
      EXPECT_LT(shadowed, rays * 19 / 20);
      EXPECT_LE(double(disagree), 1e-4 * double(rays)) << disagree << " of " << rays;
      EXPECT_EQ(not_grazing, 0u);
    }
}

// Touching and overlapping spheres: no light passes between them.
TEST(Light, NoLightPassesBetweenTouchingOrOverlappingSpheres) {
  api::scene p;
  p.spheres = {sphere{point3(0, 0, -5), 1.0}, sphere{point3(2, 0, -5), 1.0}, sphere{point3(0, 1.5, -5), 1.0}};
  p.light.direction = vec3(0, 1, 0);
  p.light.shadows = true;
  p.light.ao_samples = 8;
  const scene s = raycast::make_scene(p);
  for (const int width : light_widths()) {
    const light_structures ls = structures_of(s, width);
    const sphere_bvh& g = ls.bvh();
    const double unit = std::ldexp(1.0, -g.scale_exp);
    const auto grid_point = [&](const point3& w, float out[3]) {
      for (int a = 0; a < 3; ++a) out[a] = float((w[a] - g.origin[a]) * unit);
    };
    const auto one = [&](const float o[3], const float n[3], const float d[3]) {
      const float dir[1][3] = {{d[0], d[1], d[2]}};
      return ao_blocked(ls.rays(), 0, o, n, false, dir, 1) != 0;
    };
    // From sphere 0's point of contact with sphere 1, any ray into sphere 1's side.
    float o[3];
    grid_point(point3(1, 0, -5), o);
    const float right[3] = {1, 0, 0}, along[3] = {0.6f, 0.8f, 0.0f}, grazing_up[3] = {0.001f, 0.9999995f, 0.0f};
    EXPECT_TRUE(one(o, right, along));
    EXPECT_TRUE(one(o, right, grazing_up));
    // From sphere 0's surface inside sphere 2 (they overlap): blocked whatever the direction.
    grid_point(point3(0, 1, -5), o);
    const float up[3] = {0, 1, 0}, side[3] = {0.6f, 0.8f, 0.0f};
    EXPECT_TRUE(one(o, up, up));
    EXPECT_TRUE(one(o, up, side));
    EXPECT_TRUE(shadow_blocked(ls.rays(), 0, o, false));
    // Away from both, open.
    grid_point(point3(-1, 0, -5), o);
    const float left[3] = {-1, 0, 0};
    EXPECT_FALSE(one(o, left, left));
  }
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
