// Spheres (the book's ch. 5-6; issue 13):
//  - the double reference reproduces the book's own formulas, computed here
//    independently (ch. 5's hit_sphere, ch. 6's first normals, ch. 6's world),
//    and a few named pixels;
//  - scenes: the built-in names, and invalid spheres naming their path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "render_support.h"
#include "scene/builtin.h"

namespace {

using namespace raycast;
using raycast_test::image;

scene builtin(const std::string& name, int64_t w = 400, std::optional<int64_t> h = std::nullopt) {
  camera_params p;
  p.image_width = w;
  p.image_height = h;
  return raycast_test::make_scene(p, {}, *builtin_spheres(name));
}

// ------------------------------------------------------------ the book's formulas

// The lesson's sky, written out again (ch. 4).
color book_sky(const vec3& dir) {
  const vec3 unit = dir / glm::length(dir);
  const double t = 0.5 * (unit.y + 1.0);
  return (1.0 - t) * color(1.0, 1.0, 1.0) + t * color(0.5, 0.7, 1.0);
}

// Ch. 5: hit_sphere with the full quadratic; red where disc > 0.
color book_ch5(const ray& r) {
  const point3 center(0, 0, -1);
  const vec3 oc = r.origin() - center;
  const double a = glm::dot(r.direction(), r.direction());
  const double b = 2.0 * glm::dot(oc, r.direction());
  const double c = glm::dot(oc, oc) - 0.5 * 0.5;
  if (b * b - 4 * a * c > 0) return color(1, 0, 0);
  return book_sky(r.direction());
}

// Ch. 6, first part: t = (-b - sqrt(disc)) / (2a), N = unit(P(t) - C).
color book_ch6_normals(const ray& r) {
  const point3 center(0, 0, -1);
  const vec3 oc = r.origin() - center;
  const double a = glm::dot(r.direction(), r.direction());
  const double b = 2.0 * glm::dot(oc, r.direction());
  const double c = glm::dot(oc, oc) - 0.5 * 0.5;
  const double disc = b * b - 4 * a * c;
  const double t = disc < 0 ? -1.0 : (-b - std::sqrt(disc)) / (2.0 * a);
  if (t > 0.0) {
    const vec3 n = glm::normalize(r.at(t) - center);
    return 0.5 * color(n.x + 1, n.y + 1, n.z + 1);
  }
  return book_sky(r.direction());
}

// Ch. 6's end: the half_b form over the two spheres, nearest t in [0, inf).
color book_ch6_world(const ray& r) {
  const point3 centers[2] = {{0, 0, -1}, {0, -100.5, -1}};
  const double radii[2] = {0.5, 100};
  double closest = INFINITY;
  vec3 normal(0.0);
  for (int k = 0; k < 2; ++k) {
    const vec3 oc = r.origin() - centers[k];
    const double a = glm::dot(r.direction(), r.direction());
    const double half_b = glm::dot(oc, r.direction());
    const double c = glm::dot(oc, oc) - radii[k] * radii[k];
    const double disc = half_b * half_b - a * c;
    if (disc < 0) continue;
    double root = (-half_b - std::sqrt(disc)) / a;
    if (root < 0 || closest < root) {
      root = (-half_b + std::sqrt(disc)) / a;
      if (root < 0 || closest < root) continue;
    }
    closest = root;
    normal = (r.at(root) - centers[k]) / radii[k];
    if (glm::dot(r.direction(), normal) > 0) normal = -normal;
  }
  if (closest == INFINITY) return book_sky(r.direction());
  return 0.5 * (normal + color(1, 1, 1));
}

// The reference against one of the book's formulas, pixel by pixel, 8-bit.
void expect_reference_is_the_book(const scene& s, color (*book)(const ray&)) {
  const image ref = raycast_test::render_with_reference(s, pixel_format::rgb8);
  int64_t differing = 0;
  for (int64_t row = 0; row < ref.height; ++row)
    for (int64_t i = 0; i < ref.width; ++i) {
      const int64_t j = ref.height - 1 - row;
      const color want = book(s.cam.get_ray(s.cam.u_of(i), s.cam.v_of(j)));
      for (int k = 0; k < 3; ++k) {
        const int d = std::abs(ref.byte(row, i, k) - int(to_byte(want[k])));
        ASSERT_LE(d, 1) << "row " << row << " column " << i << " channel " << k;
        differing += d != 0;
      }
    }
  // The formulas differ in rounding only (1e-16): a byte may tip, rarely.
  EXPECT_LE(differing, 4);
}

TEST(BookChapters, Chapter5RedSphere) { expect_reference_is_the_book(builtin("red-sphere"), book_ch5); }
TEST(BookChapters, Chapter6Normals) { expect_reference_is_the_book(builtin("normals"), book_ch6_normals); }
TEST(BookChapters, Chapter6World) { expect_reference_is_the_book(builtin("world"), book_ch6_world); }

// Named pixels at 401x225, where column 200 and row 112 are the exact centre
// (u = v = 0.5, direction (0, 0, -1)).
TEST(BookChapters, NamedPixels) {
  const scene red = builtin("red-sphere", 401);
  ASSERT_EQ(red.cam.image_height, 225);
  const color centre_red = reference_pixel(red, 200, 112);
  EXPECT_EQ(centre_red, color(1, 0, 0));
  // The centre of `normals` sees the sphere's front, N = (0, 0, 1):
  // 0.5 (N + 1) = (0.5, 0.5, 1) -> 127 127 255.
  const image normals = raycast_test::render_with_reference(builtin("normals", 401), pixel_format::rgb8);
  EXPECT_EQ(normals.byte(112, 200, 0), 127);
  EXPECT_EQ(normals.byte(112, 200, 1), 127);
  EXPECT_EQ(normals.byte(112, 200, 2), 255);
  // A corner of `normals` misses: the sky's top-left check value (SPEC.md).
  EXPECT_EQ(normals.byte(0, 0, 0), 163);
  // The bottom centre of `world` (direction (0, -1, -1)) hits the ground:
  // solve |(0, 100.5 - t, 1 - t)|^2 = 100^2 by hand.
  const scene world = builtin("world", 401);
  const double bq = -(100.5 + 1.0), cq = (100.5 * 100.5 + 1.0 - 100.0 * 100.0) / 2.0;  // t^2 + bq t + cq = 0
  const double t = (-bq - std::sqrt(bq * bq - 4 * cq)) / 2.0;
  const vec3 n = (vec3(0, -t, -t) - vec3(0, -100.5, -1)) / 100.0;
  const color want = 0.5 * (n + 1.0);
  const color got = reference_pixel(world, 200, 0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-12) << k;
  EXPECT_GT(got.g, 0.99);  // the ground faces up
}

// ------------------------------------------------------------ scenes

TEST(Scenes, BuiltInNames) {
  std::vector<std::string> names;
  for (std::string_view n : builtin_scene_names()) names.emplace_back(n);
  EXPECT_EQ(names, (std::vector<std::string>{"sky", "red-sphere", "normals", "world"}));
  EXPECT_TRUE(builtin_spheres("sky")->empty());
  EXPECT_FALSE(builtin_spheres("cornell-box"));
  EXPECT_EQ(builtin_scene_list(), "sky, red-sphere, normals, world");
}

TEST(Scenes, InvalidSpheresNameTheirPath) {
  scene_params p;
  p.spheres = *builtin_spheres("world");
  EXPECT_FALSE(validate(p));
  for (double bad : {0.0, -1.0, double(INFINITY), double(NAN)}) {
    p.spheres.push_back({{0, 0, -1}, bad});
    auto e = validate(p);
    ASSERT_TRUE(e);
    EXPECT_EQ(path(*e), "spheres[2].radius");
    p.spheres.pop_back();
  }
  p.spheres[1].center.y = NAN;
  ASSERT_TRUE(validate(p));
  EXPECT_EQ(path(*validate(p)), "spheres[1].center");
  p.spheres[1].center.y = 0;
  p.spheres[0].shade = shading::flat;
  p.spheres[0].flat_color = {0, INFINITY, 0};
  ASSERT_TRUE(validate(p));
  EXPECT_EQ(path(*validate(p)), "spheres[0].color");
  p.spheres[0].shade = shading::normal;  // a normal-shaded sphere's colour is not read
  EXPECT_FALSE(validate(p));
  EXPECT_EQ(path({scene_field::vfov, "", 0}), "camera.vfov");
}

}  // namespace
