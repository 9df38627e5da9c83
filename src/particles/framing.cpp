#include "particles/framing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/vec.h"

namespace raycast {
namespace {

// The cell's corners, else the corners of the particles' bounds.
std::vector<vec3> corners_of(const particle_frame& f) {
  std::vector<vec3> c;
  if (f.cell) {
    const vec3 o = to_glm(f.cell->origin), a = to_glm(f.cell->a), b = to_glm(f.cell->b), e = to_glm(f.cell->c);
    for (int k = 0; k < 8; ++k) c.push_back(o + double(k & 1) * a + double((k >> 1) & 1) * b + double(k >> 2) * e);
    return c;
  }
  vec3 lo(INFINITY), hi(-INFINITY);
  for (size_t k = 0; k < f.count; ++k)
    for (int i = 0; i < 3; ++i) {
      const double x = f.positions.get(k, i);
      lo[i] = std::min(lo[i], x), hi[i] = std::max(hi[i], x);
    }
  if (f.count == 0) lo = hi = vec3(0.0);
  for (int k = 0; k < 8; ++k) c.push_back(vec3(k & 1 ? hi.x : lo.x, (k >> 1) & 1 ? hi.y : lo.y, k >> 2 ? hi.z : lo.z));
  return c;
}

// The unit direction from the centre toward the camera, and up.
void directions(std::string_view view, vec3& toward, vec3& up) {
  up = vec3(0, 0, 1);
  if (view == "x") toward = vec3(1, 0, 0);
  else if (view == "y") toward = vec3(0, -1, 0);
  else if (view == "z") toward = vec3(0, 0, 1), up = vec3(0, 1, 0);
  else toward = glm::normalize(vec3(1, 1, 1));
}

}  // namespace

framed_camera frame_camera(const particle_frame& f, double r_max, std::string_view view, api::projection projection,
                           double vfov, double aspect) {
  const std::vector<vec3> corners = corners_of(f);
  vec3 centre(0.0);
  for (const vec3& p : corners) centre += p / 8.0;
  vec3 w, up;
  directions(view, w, up);
  const vec3 u = glm::normalize(glm::cross(up, w)), v = glm::cross(w, u);
  // Every corner, with the largest radius around it, inside the view.
  const double r = std::max(r_max, 0.0), spare = 1.02;
  double half_h = 0, half_w = 0, nearest = 0, reach = 0;  // reach: how far toward the camera a corner lies
  for (const vec3& p : corners) {
    const vec3 d = p - centre;
    half_w = std::max(half_w, std::abs(glm::dot(d, u)) + r);
    half_h = std::max(half_h, std::abs(glm::dot(d, v)) + r);
    reach = std::max(reach, glm::dot(d, w) + r);
  }
  if (half_w == 0 && half_h == 0) half_h = half_w = 1.0;  // one point, no radius: a unit around it
  framed_camera c;
  c.lookat = centre;
  c.vup = up;
  if (projection == api::projection::orthographic) {
    c.viewport_height = spare * 2.0 * std::max(half_h, half_w / aspect);
    c.lookfrom = centre + (reach + spare * std::max(half_h, half_w)) * w;  // the plane in front of every particle
    return c;
  }
  c.vfov = vfov;
  const double tv = std::tan(vfov * std::numbers::pi / 360.0), th = tv * aspect;
  for (const vec3& p : corners) {
    const vec3 d = p - centre;
    const double depth = glm::dot(d, w);  // toward the camera
    nearest = std::max({nearest, depth + (std::abs(glm::dot(d, u)) + r) * spare / th,
                        depth + (std::abs(glm::dot(d, v)) + r) * spare / tv});
  }
  c.lookfrom = centre + std::max(nearest, reach + r) * w;
  return c;
}

}  // namespace raycast
