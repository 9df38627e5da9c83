// The lesson's pinhole camera (src/scene/README.md, "The lesson"): an axis-aligned viewport
// `focal_length` in front of the origin, spanned by `horizontal` and `vertical`;
// optionally the book's positionable camera (look-at, view-up, vertical field
// of view), which tilts that viewport.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "scene/invalid.h"
#include "raycast/description.h"
#include "scene/vec.h"

namespace raycast {

// A ray P(t) = A + t*b: origin A, direction b (not necessarily unit length).
struct ray {
  point3 orig{0.0};
  vec3 dir{0.0};

  ray() = default;
  ray(const point3& origin, const vec3& direction) : orig(origin), dir(direction) {}

  point3 origin() const { return orig; }
  vec3 direction() const { return dir; }
  point3 at(double t) const { return orig + t * dir; }
};


// Largest width or height we render. Pixel indices are converted to float by the
// float and SIMD renderers; every integer up to 2^24 is exact in float.
inline constexpr int64_t max_dimension = int64_t{1} << 24;

using api::projection;

struct camera {
  projection proj = projection::perspective;
  int64_t image_width = 0;
  int64_t image_height = 0;
  double aspect_ratio = 0;
  double viewport_height = 0;
  double viewport_width = 0;
  double focal_length = 0;
  point3 origin{0.0};
  vec3 horizontal{0.0};
  vec3 vertical{0.0};
  point3 lower_left_corner{0.0};
  // The camera's frame: w points backwards (from lookat to lookfrom), u to the
  // right, v up; (1,0,0), (0,1,0), (0,0,1) for the lesson's camera.
  vec3 axis_u{1.0, 0.0, 0.0}, axis_v{0.0, 1.0, 0.0}, axis_w{0.0, 0.0, 1.0};
  // lower_left_corner - origin, formed from its parts (-horizontal/2 -
  // vertical/2 - focal) and never by subtracting a far-away origin from a point
  // near it: the sky depends on the direction only.
  vec3 corner_dir{0.0};

  // u, v in [0, 1]: the ray through the viewport point lower_left_corner +
  // u*horizontal + v*vertical. Orthographic: the ray from the image plane's
  // point origin + (u - 1/2) horizontal + (v - 1/2) vertical along -w (the
  // plane through lookfrom, viewport_height high; focal_length unused).
  ray get_ray(double u, double v) const {
    if (proj == projection::orthographic)
      return ray(origin + (u - 0.5) * horizontal + (v - 0.5) * vertical, -axis_w);
    return ray(origin, corner_dir + u * horizontal + v * vertical);
  }
  // u and v of pixel column i and row j (j = 0 is the bottom row); the centre
  // when the image is one pixel wide or tall.
  double u_of(int64_t i) const {
    return image_width == 1 ? 0.5 : double(i) / double(image_width - 1);
  }
  double v_of(int64_t j) const {
    return image_height == 1 ? 0.5 : double(j) / double(image_height - 1);
  }
};

// int(width / aspect), never below 1 (the lesson's formula gives 0 for very
// wide aspects).
int64_t default_height(int64_t width, double aspect_ratio);

// Why the parameters cannot make a camera (non-finite or non-positive sizes,
// dimensions over the limit, lookfrom = lookat, vup parallel to the view
// direction, vfov outside (0, 180)), naming the field; nullopt when they can.
// The one place these rules live: callers do not repeat them.
std::optional<invalid_field> validate(const api::camera& p);

// Builds the camera; the parameters must pass validate().
camera make_camera(const api::camera& p);

}  // namespace raycast
