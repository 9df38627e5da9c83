#include "sphere_numerics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "cases.h"
#include "prepare/float_scene.h"
#include "kernels/scalar.h"
#include "reference/hittable.h"
#include "reference/reference.h"
#include "render/render.h"

namespace raycast_test {
namespace {

using namespace raycast;

constexpr double pi = 3.14159265358979323846;

api::camera width_200() {
  api::camera p;
  p.width = 200;
  return p;
}

// A unit sphere d radii away, filling about half the image: the textbook
// b^2 - c in float renders it as a solid square at 4100 (Ray Tracing Gems ch. 7).
sphere_stiff_case unit_sphere_at(double d) {
  api::camera p = width_200();
  p.lookat = point3(0, 0, -1);
  p.vfov = 2.0 * std::atan(2.0 / d) * 180.0 / pi;
  return {"unit_sphere_at_" + std::to_string(int(d)), {{{0, 0, -d}, 1.0, shading::normal}}, p};
}

// The camera 0.5 above a ground sphere of radius r, looking at its horizon:
// the forward tangent ray (depression beta - alpha, beta the depression of the
// centre, alpha the tangent cone's half-angle) is the image's centre, so the
// middle rows graze the surface.
sphere_stiff_case ground_grazing(double r) {
  const double D = std::sqrt((r + 0.5) * (r + 0.5) + 1.0);
  const double depression = std::atan(r + 0.5) - std::asin(r / D);
  api::camera p = width_200();
  p.lookat = point3(0, -std::tan(depression), -1);
  p.vfov = 10;
  return {"ground_radius_" + std::to_string(int64_t(r)) + "_grazing",
          {{{0, -r - 0.5, -1}, r, shading::normal}}, p};
}

// A circle of radius 65 = 5 * 13 grid steps passes through 36 lattice points
// (65^2 = 0^2 + 65^2 = 16^2 + 63^2 = 25^2 + 60^2 = 33^2 + 56^2 = 39^2 + 52^2).
// At 161 x 161 pixels over a 2 x 2 viewport at focal length 1 the pixel
// centres are that lattice with step 1/80 around the centre pixel, so a sphere
// on the axis whose silhouette has radius 65/80 on the viewport makes those
// 36 rays tangent (to the rounding of r): half of them hit in double, half
// not. A larger sphere behind turns the misses into other-object pixels.
sphere_stiff_case tangent_rays() {
  api::camera p;
  p.aspect = 1.0;
  p.width = 161;
  p.height = 161;
  const double rho = 65.0 / 80.0, d = 2.0;
  const double r = d * rho / std::sqrt(1.0 + rho * rho);  // sin(atan(rho)) d
  return {"tangent_rays", {{{0, 0, -d}, r, shading::normal}, {{0, 0, -20}, 15.0, shading::normal}}, p};
}

// The camera and the spheres near 1e30, the scene 1e28 across: float
// coordinates there are 8e22 apart (1e-5 of the scene), and r^2 overflows float.
sphere_stiff_case coordinates_near_1e30() {
  api::camera p = width_200();
  const point3 o(1.1e30, -0.7e30, 2.3e30);
  const double k = 1e28;
  p.lookfrom = o;
  return {"coordinates_near_1e30",
          {{o + k * vec3(0, 0, -1), 0.5 * k, shading::normal},
           {o + k * vec3(0.9, 0.2, -1.6), 0.45 * k, shading::normal},
           {o + k * vec3(0, -100.5, -1), 100 * k, shading::normal}},
          p};
}

// The book's ch. 6 world with the camera's origin, viewport and focal length,
// the centres and the radii all multiplied by s: the same picture at every s.
// (The origin is moved off 0 so that it scales too.)
sphere_stiff_case world_scaled(double s, const std::string& suffix) {
  api::camera p = width_200();
  p.viewport_height = 2.0 * s;
  p.focal_length = s;
  const vec3 o(1, 2, 3);
  p.lookfrom = s * o;
  return {"world_scaled_" + suffix,
          {{s * (o + vec3(0, 0, -1)), 0.5 * s, shading::normal},
           {s * (o + vec3(0, -100.5, -1)), 100 * s, shading::normal}},
          p};
}

// The ch. 6 world through a lens of focal length 10^-19 of its viewport: the
// centre ray's direction is 10^-19 long next to its neighbours' (the camera
// vectors are scaled so their largest component is near 1), and only that
// ray hits the sphere ahead. Its squared length is below float's normal range.
// A camera whose viewport centre is a vanishing fraction of the viewport:
// the focal length 10^-19, 10^-30 and 10^-36 of it (below float's range
// of the viewport from 2^-100 on), or the viewport 10^150 times the focal
// length (about the largest the reference's squares of the direction hold).
// 401 x 225 pixels: one pixel sees the viewport's centre, and only that
// ray reaches the sphere ahead.
sphere_stiff_case degenerate_camera(const std::string& name, double focal_length, double viewport_height = 2.0) {
  api::camera p;
  p.width = 401;
  p.height = 225;
  p.focal_length = focal_length;
  p.viewport_height = viewport_height;
  return {name, {{{0, 0, -1}, 0.5, shading::normal}, {{0, -100.5, -1}, 100, shading::normal}}, p};
}

// The ch. 6 world through an orthographic camera (scene/camera.h), its
// image plane viewport_height high: at the world's own size (the plane cuts
// the ground sphere, whose inside the lower rows see), scaled by 10^-6 and
// 10^6 (the same picture), from 10^7 away along the view (the plane offset
// keeps the depths' precision), and with a sphere behind the plane and one
// the plane cuts.
sphere_stiff_case orthographic(const std::string& name, double scale, double back) {
  api::camera p = width_200();
  p.projection = projection::orthographic;
  p.viewport_height = 3.0 * scale;
  p.lookfrom = point3(0.0, 0.0, back);
  std::vector<sphere> world = {{{0, 0, -1}, 0.5, shading::normal}, {{0, -100.5, -1}, 100, shading::normal}};
  for (sphere& b : world) b.center = to_glm(b.center) * scale, b.radius *= scale;
  return {name, world, p};
}

sphere_stiff_case orthographic_plane_cuts() {
  api::camera p = width_200();
  p.projection = projection::orthographic;
  p.viewport_height = 3.0;
  return {"ortho_spheres_behind_and_cut",
          {{{0.6, 0.0, 2.0}, 0.5, shading::normal},     // behind the image plane: never seen
           {{-0.6, 0.2, -0.1}, 0.5, shading::normal},   // cut by it: its inside where rays start in it
           {{0.3, -0.3, -1.5}, 0.6, shading::normal}},  // in front
          p};
}

std::vector<sphere_stiff_case> make_cases() {
  std::vector<sphere_stiff_case> v;
  for (double d : {10.0, 100.0, 1e3, 4100.0, 1e4, 1e5, 1e6, 1e7}) v.push_back(unit_sphere_at(d));
  for (double r : {100.0, 1e4, 1e6}) v.push_back(ground_grazing(r));
  const api::camera p = width_200();
  v.push_back({"camera_touching", {{{0, 0, -0.5}, 0.5, shading::normal}, {{0, 0, -2}, 0.5, shading::normal}}, p});
  v.push_back({"camera_inside", {{{0.2, 0.1, -0.3}, 3.0, shading::normal}}, p});
  v.push_back({"camera_on_the_ground", {{{0, -1000, 0}, 1000, shading::normal}, {{0, 0, -2}, 0.5, shading::normal}}, p});
  v.push_back({"sphere_behind_camera", {{{0, 0, 2}, 1.0, shading::normal}, {{0, 0, -2}, 0.5, shading::normal}}, p});
  v.push_back(tangent_rays());
  v.push_back(coordinates_near_1e30());
  for (const auto& [s, suffix] : {std::pair{1e-30, "1e-30"}, {1e-10, "1e-10"}, {1e10, "1e10"}, {1e30, "1e30"}})
    v.push_back(world_scaled(s, suffix));
  v.push_back(degenerate_camera("focal_length_1e-19", 1e-19));
  v.push_back(degenerate_camera("focal_length_1e-30", 1e-30));
  v.push_back(degenerate_camera("focal_length_1e-36", 1e-36));
  v.push_back(degenerate_camera("viewport_1e150", 1.0, 1e150));
  v.push_back(orthographic("ortho_world", 1.0, 0.0));
  v.push_back(orthographic("ortho_viewport_3e-6", 1e-6, 0.0));
  v.push_back(orthographic("ortho_viewport_3e6", 1e6, 0.0));
  v.push_back(orthographic("ortho_camera_at_1e7", 1.0, 1e7));
  v.push_back(orthographic_plane_cuts());
  return v;
}

traced_image blank(const scene& s) {
  traced_image t;
  t.width = s.cam.image_width;
  t.height = s.cam.image_height;
  t.sphere.assign(size_t(t.width * t.height), -1);
  t.distance.assign(size_t(t.width * t.height), 0.0);
  t.rgb8.assign(size_t(t.width * t.height) * 3, 0);
  return t;
}

// NaN (the book's float arithmetic at 1e30 and beyond) is 0, as x86's
// conversion makes it (and without the conversion's undefined behaviour).
unsigned char byte_of(float c) {
  if (std::isnan(c)) return 0;
  return static_cast<unsigned char>(int(std::clamp(c, 0.0f, 1.0f) * 255.999f));
}

struct f3 {
  float x, y, z;
};
f3 operator-(f3 a, f3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
float dot(f3 a, f3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
f3 to_f3(const vec3& v) { return {float(v.x), float(v.y), float(v.z)}; }

// The book's sphere::hit in float; t_max the closest hit so far.
bool naive_hit(const f3& o, const f3& d, const f3& c, float r, float t_max, float& t) {
  const f3 oc = o - c;
  const float a = dot(d, d);
  const float half_b = dot(oc, d);
  const float cc = dot(oc, oc) - r * r;
  const float disc = half_b * half_b - a * cc;
  if (disc < 0) return false;
  const float sqrtd = std::sqrt(disc);
  float root = (-half_b - sqrtd) / a;
  if (root < 0 || t_max < root) {
    root = (-half_b + sqrtd) / a;
    if (root < 0 || t_max < root) return false;
  }
  t = root;
  return true;
}

// The sky in float, as the peers shade it (bench/embree_peer.cpp).
void naive_sky(const sky& sk, const f3& d, float out[3]) {
  const float len = std::sqrt(std::max(dot(d, d), std::numeric_limits<float>::min()));
  const float t = (d.y / len + 1.0f) * 0.5f;
  for (int k = 0; k < 3; ++k) {
    const float b = float(sk.bottom[k]), tp = float(sk.top[k]);
    out[k] = std::clamp(b + t * (tp - b), std::min(b, tp), std::max(b, tp));
  }
}

}  // namespace

double farthest_in_radii(const sphere_stiff_case& c) {
  double most = 0.0;
  for (const sphere& b : c.spheres) most = std::max(most, glm::length(to_glm(c.cam.lookfrom) - to_glm(b.center)) / b.radius);
  return most;
}

int contract_lsb(double distance_in_radii) {
  return distance_in_radii <= 1e5 ? 1 : 1 + int(distance_in_radii / 1e5);
}

const std::vector<sphere_stiff_case>& sphere_stiff_cases() {
  static const std::vector<sphere_stiff_case> all = make_cases();
  return all;
}

scene scene_of(const sphere_stiff_case& c) { return make_scene(c.cam, {}, c.spheres); }

traced_image trace_reference(const scene& s) {
  traced_image t = blank(s);
  render_reference(s, image_band{t.rgb8.data(), size_t(t.width) * 3, pixel_format::rgb8, 0, t.height});
  for (int64_t row = 0; row < t.height; ++row)
    for (int64_t i = 0; i < t.width; ++i) {
      const ray r = s.cam.get_ray(s.cam.u_of(i), s.cam.v_of(t.height - 1 - row));
      hit_record rec;
      if (!hit_world(s.spheres, r, 0.0, INFINITY, rec)) continue;
      t.sphere[t.at(row, i)] = rec.object - s.spheres.data();
      t.distance[t.at(row, i)] = rec.t * glm::length(r.direction());
    }
  return t;
}

traced_image trace_ours(const scene& s) {
  traced_image t = blank(s);
  const float_scene f = prepare_float_scene(s);
  render_options o;
  o.which = backend::scalar;
  o.threads = 1;
  renderer(s, o).render(image_band{t.rgb8.data(), size_t(t.width) * 3, pixel_format::rgb8, 0, t.height});
  for (int64_t row = 0; row < t.height; ++row)
    for (int64_t i = 0; i < t.width; ++i) {
      const scalar_hit h = scalar_trace(f, i, t.height - 1 - row);
      t.sphere[t.at(row, i)] = h.sphere;
      t.distance[t.at(row, i)] = h.distance;
    }
  return t;
}

traced_image trace_naive(const scene& s) {
  traced_image t = blank(s);
  for (int64_t row = 0; row < t.height; ++row)
    for (int64_t i = 0; i < t.width; ++i) {
      const ray rd = s.cam.get_ray(s.cam.u_of(i), s.cam.v_of(t.height - 1 - row));  // orthographic: its own origin
      const f3 o = to_f3(rd.origin()), d = to_f3(rd.direction());
      float closest = std::numeric_limits<float>::infinity(), tk = 0;
      int64_t hit = -1;
      for (size_t k = 0; k < s.spheres.size(); ++k)
        if (naive_hit(o, d, to_f3(to_glm(s.spheres[k].center)), float(s.spheres[k].radius), closest, tk)) {
          closest = tk;
          hit = int64_t(k);
        }
      float c[3];
      if (hit < 0) {
        naive_sky(s.sky, d, c);
      } else if (const sphere& sp = s.spheres[size_t(hit)]; sp.shade == shading::flat) {
        for (int k = 0; k < 3; ++k) c[k] = float(sp.color[k]);
      } else {
        const f3 ctr = to_f3(to_glm(sp.center));
        const float r = float(sp.radius);
        f3 n = {(o.x + closest * d.x - ctr.x) / r, (o.y + closest * d.y - ctr.y) / r,
                (o.z + closest * d.z - ctr.z) / r};
        if (dot(d, n) > 0) n = {-n.x, -n.y, -n.z};
        c[0] = 0.5f * (n.x + 1.0f);
        c[1] = 0.5f * (n.y + 1.0f);
        c[2] = 0.5f * (n.z + 1.0f);
      }
      const size_t p = t.at(row, i);
      t.sphere[p] = hit;
      t.distance[p] = hit < 0 ? 0.0 : double(closest) * std::sqrt(double(dot(d, d)));
      for (int k = 0; k < 3; ++k) t.rgb8[3 * p + size_t(k)] = byte_of(c[k]);
    }
  return t;
}

sphere_metrics measure(const traced_image& ref, const traced_image& got) {
  sphere_metrics m;
  const int64_t W = ref.width, H = ref.height;
  m.pixels = W * H;
  for (int64_t row = 0; row < H; ++row)
    for (int64_t i = 0; i < W; ++i) {
      const size_t p = ref.at(row, i);
      bool away = true;
      for (int64_t rr = std::max<int64_t>(0, row - 1); rr <= std::min(H - 1, row + 1); ++rr)
        for (int64_t ii = std::max<int64_t>(0, i - 1); ii <= std::min(W - 1, i + 1); ++ii)
          away = away && ref.sphere[ref.at(rr, ii)] == ref.sphere[p];
      m.silhouette_pixels += !away;
      const int64_t want = ref.sphere[p], have = got.sphere[p];
      const bool false_hit = want < 0 && have >= 0, false_miss = want >= 0 && have < 0;
      const bool wrong = want >= 0 && have >= 0 && want != have;
      m.false_hits += false_hit;
      m.false_misses += false_miss;
      m.wrong_object += wrong;
      if (away) {
        m.false_hits_away += false_hit;
        m.false_misses_away += false_miss;
        m.wrong_object_away += wrong;
      }
      if (want < 0) continue;
      if (away && want == have) {
        const double r = ref.distance[p], g = got.distance[p];
        double e = std::abs(g - r) / r;
        if (r == 0) e = g == 0 ? 0.0 : INFINITY;
        if (std::isnan(e)) e = INFINITY;
        m.max_rel_distance_err = std::max(m.max_rel_distance_err, e);
      }
      for (size_t k = 0; k < 3; ++k) {
        const int lsb = std::abs(int(got.rgb8[3 * p + k]) - int(ref.rgb8[3 * p + k]));
        m.max_lsb = std::max(m.max_lsb, lsb);
        if (away) m.max_lsb_away = std::max(m.max_lsb_away, lsb);
      }
    }
  return m;
}

bool no_worse(const sphere_metrics& a, const sphere_metrics& b) {
  return a.false_hits <= b.false_hits && a.false_hits_away <= b.false_hits_away &&
         a.false_misses <= b.false_misses && a.false_misses_away <= b.false_misses_away &&
         a.wrong_object <= b.wrong_object && a.wrong_object_away <= b.wrong_object_away &&
         a.max_rel_distance_err <= b.max_rel_distance_err && a.max_lsb_away <= b.max_lsb_away &&
         a.max_lsb <= b.max_lsb;
}

}  // namespace raycast_test
