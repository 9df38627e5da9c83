// What one render needs: the camera and the sky it looks at.
#pragma once
#include "scene/camera.h"
#include "scene/sky.h"

namespace raycast {

struct scene {
  camera cam;
  raycast::sky sky;
};

}  // namespace raycast
