#include "camera.h"

#include <cmath>

namespace raycast {

int64_t default_height(int64_t width, double aspect_ratio) {
  const double h = double(width) / aspect_ratio;
  if (!(h >= 1.0)) return 1;
  if (h >= double(max_dimension)) return max_dimension + 1;  // refused by validate()
  return static_cast<int64_t>(h);
}

std::optional<std::string> validate(const camera_params& p) {
  auto positive_finite = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive_finite(p.aspect_ratio)) return "aspect ratio must be a positive finite number";
  if (!positive_finite(p.viewport_height)) return "viewport height must be a positive finite number";
  if (!positive_finite(p.focal_length)) return "focal length must be a positive finite number";
  if (!positive_finite(p.aspect_ratio * p.viewport_height))
    return "viewport width (aspect x viewport height) overflows a double";
  for (double c : {p.origin.x, p.origin.y, p.origin.z})
    if (!std::isfinite(c)) return "origin must be finite";
  const auto dims_ok = [](int64_t n) { return n >= 1 && n <= max_dimension; };
  if (!dims_ok(p.image_width))
    return "width must be between 1 and " + std::to_string(max_dimension);
  const int64_t h = p.image_height.value_or(default_height(p.image_width, p.aspect_ratio));
  if (!dims_ok(h)) return "height must be between 1 and " + std::to_string(max_dimension);
  return std::nullopt;
}

camera make_camera(const camera_params& p) {
  camera c;
  c.image_width = p.image_width;
  c.image_height = p.image_height.value_or(default_height(p.image_width, p.aspect_ratio));
  c.aspect_ratio = p.aspect_ratio;
  c.viewport_height = p.viewport_height;
  c.viewport_width = p.aspect_ratio * p.viewport_height;
  c.focal_length = p.focal_length;
  c.origin = p.origin;
  c.horizontal = vec3(c.viewport_width, 0.0, 0.0);
  c.vertical = vec3(0.0, c.viewport_height, 0.0);
  c.corner_dir = -c.horizontal / 2.0 - c.vertical / 2.0 - vec3(0.0, 0.0, c.focal_length);
  c.lower_left_corner = c.origin + c.corner_dir;
  return c;
}

}  // namespace raycast
