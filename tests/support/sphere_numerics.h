// The stiff sphere cases and the measurement of a renderer's numerics
// on them against the double reference, shared by tests/test_sphere_stiff.cpp
// and raycast-bench's stiff section (src/kernels/README.md, "Spheres: stiff cases").
//
// A renderer is measured through what it traced per pixel (which sphere, at
// what distance from the camera) and its 8-bit output: ours (the scalar float
// renderer in exact mode; every SIMD backend is bit-identical to it), the
// book's ch. 6 hit_sphere carried out in float (the "naïve" column) and, in
// the bench, Embree.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/sphere.h"

namespace raycast_test {

struct sphere_stiff_case {
  std::string name;
  std::vector<raycast::sphere> spheres;
  raycast::api::camera cam;
};

// unit_sphere_at_10 ... _10000000, ground_radius_100/10000/1000000_grazing,
// camera_touching, camera_inside, camera_on_the_ground, sphere_behind_camera,
// tangent_rays, coordinates_near_1e30, world_scaled_1e-30 ... _1e30 (200
// pixels wide), focal_length_1e-19, _1e-30, _1e-36 and viewport_1e150
// (401 x 225: the reference's own centre ray sees the sphere).
const std::vector<sphere_stiff_case>& sphere_stiff_cases();
raycast::scene scene_of(const sphere_stiff_case& c);

// The float contract's range (src/kernels/README.md, "Spheres: stiff cases"):
// away from silhouettes, a sphere at most 10^5 radii from the camera is
// within 1 LSB of the reference; farther, the normal's rounding (about
// 2^-24 |f| / r) shows, and it is within 1 + (|f| / r) / 10^5 LSB.
double farthest_in_radii(const sphere_stiff_case& c);  // max |lookfrom - centre| / radius
int contract_lsb(double distance_in_radii);

// What a renderer saw at every pixel, rows top first (row r is the camera's
// j = H - 1 - r).
struct traced_image {
  int64_t width = 0, height = 0;
  std::vector<int64_t> sphere;         // index of the closest sphere hit; -1 for none
  std::vector<double> distance;        // from the camera origin, world units (0: none)
  std::vector<unsigned char> rgb8;     // its 8-bit output, 3 channels packed
  size_t at(int64_t row, int64_t col) const { return size_t(row * width + col); }
};

// The double reference (hit_world: t * |d|; render_reference's bytes).
traced_image trace_reference(const raycast::scene& s);
// Ours: scalar_trace and render_scalar, exact mode.
traced_image trace_ours(const raycast::scene& s);
// The book's ch. 6 in float, from the double scene rounded to float once: the
// origin, the centre, the radius and the ray direction (formed in double from
// the camera, as Embree's user hands it over), then oc = O - C, a = d.d,
// half_b = oc.d, c = oc.oc - r^2, disc = half_b^2 - a c, root (-half_b -
// sqrt(disc)) / a else (-half_b + sqrt(disc)) / a within [0, closest], as
// hittable_list; N = (O + t d - C) / r facing the ray, 0.5 (N + 1) or the flat
// colour; the sky in float where nothing is hit; int(clamp(c) * 255.999f).
traced_image trace_naive(const raycast::scene& s);

// A renderer against the reference. "Away" counts only pixels whose 3x3
// neighbourhood in the reference sees one object (or the sky) alone: at a
// silhouette the true answer flips within a pixel, and rays there are tangent
// or nearly so.
struct sphere_metrics {
  int64_t false_hits = 0, false_hits_away = 0;      // hits where the reference misses
  int64_t false_misses = 0, false_misses_away = 0;  // misses where the reference hits
  int64_t wrong_object = 0, wrong_object_away = 0;  // both hit, a different sphere
  // |distance - reference| / reference where both hit the same sphere, away
  // from silhouettes (infinite for a NaN distance or a reference at 0 that
  // the renderer does not reproduce).
  double max_rel_distance_err = 0;
  // Largest |byte - reference byte| over pixels the reference shades from a
  // sphere: away from silhouettes, and everywhere.
  int max_lsb_away = 0, max_lsb = 0;
  int64_t pixels = 0, silhouette_pixels = 0;
};
sphere_metrics measure(const traced_image& reference, const traced_image& got);

// Every metric of a no larger than b's ("no row worse than").
bool no_worse(const sphere_metrics& a, const sphere_metrics& b);

}  // namespace raycast_test
