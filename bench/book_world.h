// The book's scene classes as they stand from ch. 6 on (Ray Tracing in One
// Weekend v3.2.3: hittable.h, sphere.h, hittable_list.h and main.cc's
// ray_color), shared by the ch. 6 and ch. 7 peers: double precision, a virtual
// `hittable` interface, a `hittable_list` of shared_ptr. The book's code, not
// an optimized version of it.
#pragma once
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/camera.h"

namespace raycast::bench::book {

// hittable.h
struct hit_record {
  point3 p;
  vec3 normal;
  double t;
  bool front_face;

  void set_face_normal(const ray& r, const vec3& outward_normal) {
    front_face = glm::dot(r.direction(), outward_normal) < 0;
    normal = front_face ? outward_normal : -outward_normal;
  }
};

class hittable {
 public:
  virtual ~hittable() = default;
  virtual bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const = 0;
};

// sphere.h
class sphere : public hittable {
 public:
  sphere(point3 cen, double r) : center(cen), radius(r) {}
  bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const override {
    const vec3 oc = r.origin() - center;
    const double a = glm::dot(r.direction(), r.direction());
    const double half_b = glm::dot(oc, r.direction());
    const double c = glm::dot(oc, oc) - radius * radius;
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
    const vec3 outward_normal = (rec.p - center) / radius;
    rec.set_face_normal(r, outward_normal);
    return true;
  }

  point3 center;
  double radius;
};

// hittable_list.h
class hittable_list : public hittable {
 public:
  void add(std::shared_ptr<hittable> object) { objects.push_back(std::move(object)); }
  bool hit(const ray& r, double t_min, double t_max, hit_record& rec) const override {
    hit_record temp_rec;
    bool hit_anything = false;
    double closest_so_far = t_max;
    for (const auto& object : objects) {
      if (object->hit(r, t_min, closest_so_far, temp_rec)) {
        hit_anything = true;
        closest_so_far = temp_rec.t;
        rec = temp_rec;
      }
    }
    return hit_anything;
  }

  std::vector<std::shared_ptr<hittable>> objects;
};

// main.cc
inline color ray_color(const ray& r, const hittable& world) {
  hit_record rec;
  if (world.hit(r, 0, std::numeric_limits<double>::infinity(), rec))
    return 0.5 * (rec.normal + color(1, 1, 1));
  const vec3 unit_direction = r.direction() / glm::length(r.direction());
  const double t = 0.5 * (unit_direction.y + 1.0);
  return (1.0 - t) * color(1.0, 1.0, 1.0) + t * color(0.5, 0.7, 1.0);
}

}  // namespace raycast::bench::book
