// The book's ch. 6 hit machinery in double (Ray Tracing in One Weekend v3.2.3), formula for formula.
#pragma once
#include <cmath>
#include <span>

#include <glm/geometric.hpp>

#include "scene/camera.h"
#include "scene/sphere.h"

namespace raycast {

struct hit_record {
  point3 p{0.0};
  vec3 normal{0.0};  // unit, facing the ray (the book's set_face_normal)
  double t = 0;
  bool front_face = true;
  const sphere* object = nullptr;
};

// sphere::hit: oc = A - C, a = |b|^2, half_b = oc.b, c = |oc|^2 - r^2, disc = half_b^2 - a c; the
// nearer root (-half_b - sqrt(disc)) / a unless outside [t_min, t_max], then the farther one.
inline bool hit_sphere(const sphere& s, const ray& r, double t_min, double t_max, hit_record& rec) {
  const vec3 oc = r.origin() - to_glm(s.center);
  const double a = glm::dot(r.direction(), r.direction());
  const double half_b = glm::dot(oc, r.direction());
  const double c = glm::dot(oc, oc) - s.radius * s.radius;
  const double discriminant = half_b * half_b - a * c;
  if (discriminant < 0) return false;
  const double sqrtd = std::sqrt(discriminant);
  double root = (-half_b - sqrtd) / a;
  if (root < t_min || t_max < root) {
    root = (-half_b + sqrtd) / a;
    if (root < t_min || t_max < root) return false;
  }
  rec.t = root;
  rec.p = r.at(rec.t);
  const vec3 outward_normal = (rec.p - to_glm(s.center)) / s.radius;
  rec.front_face = glm::dot(r.direction(), outward_normal) < 0;
  rec.normal = rec.front_face ? outward_normal : -outward_normal;
  rec.object = &s;
  return true;
}

// hittable_list::hit: every sphere in order, t_max the closest t so far (a tie: the later sphere).
inline bool hit_world(std::span<const sphere> world, const ray& r, double t_min, double t_max,
                      hit_record& rec) {
  hit_record temp;
  bool hit_anything = false;
  double closest_so_far = t_max;
  for (const sphere& s : world) {
    if (hit_sphere(s, r, t_min, closest_so_far, temp)) {
      hit_anything = true;
      closest_so_far = temp.t;
      rec = temp;
    }
  }
  return hit_anything;
}

// The secondary rays' test in double (light/secondary.h): whether o + t d, t in [0, t_max], |d| = 1,
// meets the solid ball of any sphere but skip (a start inside one is blocked).
inline bool blocked(std::span<const sphere> world, const point3& o, const vec3& d, double t_max, const sphere* skip) {
  for (const sphere& s : world) {
    if (&s == skip) continue;
    const vec3 oc = o - to_glm(s.center);
    const double r2 = s.radius * s.radius;
    if (glm::dot(oc, oc) <= r2) return true;
    const double b = glm::dot(oc, d);
    if (b >= 0.0) continue;
    const vec3 v = oc - b * d;  // from the centre to the line's nearest point
    const double m2 = glm::dot(v, v);
    if (m2 > r2) continue;
    if (-b - std::sqrt(r2 - m2) <= t_max) return true;
  }
  return false;
}

// Ambient occlusion's cosine-weighted direction of (u1, u2) about n, in Duff et al.'s frame.
inline vec3 cosine_direction(const vec3& n, double u1, double u2) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const vec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const vec3 bt(b, sign + n.y * n.y * a, -n.y);
  const double phi = 2.0 * M_PI * u1, rad = std::sqrt(u2);
  return rad * std::cos(phi) * t + rad * std::sin(phi) * bt + std::sqrt(1.0 - u2) * n;
}

}  // namespace raycast
