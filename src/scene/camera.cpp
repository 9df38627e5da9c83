#include "scene/camera.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>


namespace raycast {

int64_t default_height(int64_t width, double aspect_ratio) {
  const double h = double(width) / aspect_ratio;
  if (!(h >= 1.0)) return 1;
  if (h >= double(max_dimension)) return max_dimension + 1;  // refused by validate()
  return static_cast<int64_t>(h);
}

std::optional<invalid_field> validate(const api::camera& p) {
  using enum scene_field;
  const auto bad = [](scene_field f, std::string why) {
    return std::optional<invalid_field>(invalid_field{f, std::move(why)});
  };
  auto positive_finite = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive_finite(p.aspect)) return bad(aspect, "aspect ratio must be a positive finite number");
  if (!positive_finite(p.viewport_height))
    return bad(viewport_height, "viewport height must be a positive finite number");
  if (!positive_finite(p.focal_length))
    return bad(focal_length, "focal length must be a positive finite number");
  // Out of a double's range both ways, said as too small or too large in
  // the user's terms (a product that rounds to 0 is not an overflow).
  const auto beyond = [](double x) { return x == 0.0 ? "too small" : "too large"; };
  if (const double w = p.aspect * p.viewport_height; !positive_finite(w))
    return bad(viewport_height, std::string("viewport height is ") + beyond(w) +
                                    " for this aspect ratio: the viewport width (aspect x viewport height) is " +
                                    (w == 0.0 ? "below the smallest double" : "beyond the largest double"));
  for (double c : {p.lookfrom.x, p.lookfrom.y, p.lookfrom.z})
    if (!std::isfinite(c)) return bad(origin, "origin must be finite");
  if (p.vfov && p.projection == projection::orthographic)
    return bad(vfov, "vertical field of view means nothing for an orthographic camera (give the viewport height)");
  if (p.vfov) {
    const double f = *p.vfov;
    if (!(f > 0.0 && f < 180.0))
      return bad(vfov, "vertical field of view must be between 0 and 180 degrees (exclusive)");
    if (const double w = 2.0 * std::tan(f * std::numbers::pi / 360.0) * p.focal_length * p.aspect;
        !positive_finite(w))
      return bad(vfov, std::string("vertical field of view is ") + beyond(w) +
                           " for this focal length and aspect ratio: the viewport (2 tan(vfov/2) x focal length x "
                           "aspect) is " + (w == 0.0 ? "below the smallest double" : "beyond the largest double"));
  }
  if (p.lookat) {
    for (double c : {p.lookat->x, p.lookat->y, p.lookat->z})
      if (!std::isfinite(c)) return bad(lookat, "lookat must be finite");
    for (double c : {p.vup.x, p.vup.y, p.vup.z})
      if (!std::isfinite(c)) return bad(vup, "vup must be finite");
    const vec3 back = to_glm(p.lookfrom) - to_glm(*p.lookat);
    if (!std::isfinite(back.x) || !std::isfinite(back.y) || !std::isfinite(back.z))
      return bad(lookat, "lookat is too far from lookfrom: their difference is beyond the largest double");
    if (back == vec3(0.0)) return bad(lookat, "lookfrom and lookat are the same point");
    if (to_glm(p.vup) == vec3(0.0)) return bad(vup, "vup must not be the zero vector");
    // Parallel when the sine of the angle between them is below 1e-9.
    if (glm::length(glm::cross(unit_vector(to_glm(p.vup)), unit_vector(back))) < 1e-9)
      return bad(vup, "vup is parallel to the view direction");
  }
  const auto dims_ok = [](int64_t n) { return n >= 1 && n <= max_dimension; };
  const std::string range = " must be between 1 and " + std::to_string(max_dimension);
  if (!dims_ok(p.width))
    return bad(width, "width" + range + ", got " + std::to_string(p.width));
  if (p.height && !dims_ok(*p.height))
    return bad(height, "height" + range + ", got " + std::to_string(*p.height));
  if (!p.height && !dims_ok(default_height(p.width, p.aspect)))
    return bad(aspect, "height (width / aspect)" + range);
  return std::nullopt;
}

camera make_camera(const api::camera& p) {
  camera c;
  c.proj = p.projection;
  c.image_width = p.width;
  c.image_height = p.height.value_or(default_height(p.width, p.aspect));
  c.aspect_ratio = p.aspect;
  c.viewport_height = p.vfov
                          ? 2.0 * std::tan(*p.vfov * std::numbers::pi / 360.0) * p.focal_length
                          : p.viewport_height;
  c.viewport_width = p.aspect * c.viewport_height;
  c.focal_length = p.focal_length;
  c.origin = to_glm(p.lookfrom);
  if (p.lookat) {
    // The book's frame, from directions only: a far-away lookfrom loses
    // nothing, since the sky never reads a position.
    c.axis_w = unit_vector(c.origin - to_glm(*p.lookat));
    c.axis_u = unit_vector(glm::cross(to_glm(p.vup), c.axis_w));
    c.axis_v = glm::cross(c.axis_w, c.axis_u);
  }
  c.horizontal = c.viewport_width * c.axis_u;
  c.vertical = c.viewport_height * c.axis_v;
  c.corner_dir = -c.horizontal / 2.0 - c.vertical / 2.0 - c.focal_length * c.axis_w;
  c.lower_left_corner = c.origin + c.corner_dir;
  return c;
}

}  // namespace raycast
