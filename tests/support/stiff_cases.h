// The numerics issue's stiff and extreme inputs as a reusable list: each a
// camera and a sky the renderers must handle like the double reference does.
// Used by the benchmark's stiff section (and available to tests).
#pragma once
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/sky.h"

namespace raycast {

struct stiff_case {
  std::string name;
  camera_params cam;
  raycast::sky sky;
};

// Degenerate sizes, extreme scales, far origins and an HDR sky; every image
// has at most 400 x 225 pixels (aspect 1:100000 is 3 x 300).
std::vector<stiff_case> stiff_cases();

}  // namespace raycast
