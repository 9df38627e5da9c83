// What one render needs: the camera and the sky it looks at. A job builds its
// scene_params, validates them once here, and renders the scene they make.
#pragma once
#include <optional>

#include "scene/camera.h"
#include "scene/invalid.h"
#include "scene/sky.h"

namespace raycast {

struct scene {
  camera cam;
  raycast::sky sky;
};

// A scene as a caller describes it, before validation.
struct scene_params {
  camera_params camera;
  raycast::sky sky;
};

// The first field that cannot make a scene, or nullopt.
std::optional<invalid_field> validate(const scene_params& p);

// The scene; p must pass validate().
scene make_scene(const scene_params& p);

}  // namespace raycast
