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

// Why a sphere cannot be rendered (a non-finite centre, a radius not positive
// and finite, a flat colour not finite within +-1e30), or nullopt.
std::optional<invalid_field> validate(const sphere& s, size_t index);

// The first field that cannot make a scene, or nullopt.
std::optional<invalid_field> validate(const scene_params& p);

// The scene; p must pass validate().
scene make_scene(const scene_params& p);

}  // namespace raycast
