// What one render needs: the camera, the sky it looks at and the spheres in
// front of the sky (none: the lesson's picture). A job builds its
// scene_params, validates them once here, and renders the scene they make.
#pragma once
#include <optional>
#include <vector>

#include "scene/camera.h"
#include "scene/invalid.h"
#include "scene/sky.h"
#include "scene/sphere.h"

namespace raycast {

struct scene {
  camera cam;
  raycast::sky sky;
  std::vector<sphere> spheres;  // empty: the sky alone, today's kernel
};

// A scene as a caller describes it, before validation.
struct scene_params {
  camera_params camera;
  raycast::sky sky;
  std::vector<sphere> spheres;
};

// The largest sphere radius, and the largest distance from the camera
// (lookfrom) to a sphere's centre in any coordinate. The float renderers scale
// each sphere by a power of two 2^e with max(|lookfrom - center| components,
// radius) < 2^e and need 2^e <= 2^126 (1e37 < 2^123, with room for the ray's
// own terms); beyond it a sphere would silently vanish.
inline constexpr double max_sphere_extent = 1e37;

// Why a sphere cannot be rendered (a non-finite centre, a radius not positive
// and finite or above max_sphere_extent, a flat colour not finite within
// +-1e30), or nullopt.
std::optional<invalid_field> validate(const sphere& s, size_t index);

// The first field that cannot make a scene, or nullopt: the camera, the sky,
// each sphere and its centre within max_sphere_extent of the camera.
std::optional<invalid_field> validate(const scene_params& p);

// The scene; p must pass validate(). The second moves the spheres (a scene
// file's millions) instead of copying them.
scene make_scene(const scene_params& p);
scene make_scene(scene_params&& p);

}  // namespace raycast
