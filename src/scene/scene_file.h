// Scene files (`--scene FILE.json`): a camera, a sky and spheres as JSON.
//
//   {"camera": {"width": 400, "height": 225, "aspect": 1.7778 or "16:9",
//               "lookfrom": [x,y,z], "lookat": [x,y,z], "vup": [x,y,z],
//               "vfov": 90, "viewport_height": 2, "focal_length": 1},
//    "sky": {"bottom": [r,g,b], "top": [r,g,b]},
//    "spheres": [{"center": [x,y,z], "radius": r, "shade": "normal"},
//                {"center": [x,y,z], "radius": r, "shade": "flat", "color": [r,g,b]}]}
//
// Every key is optional (the lesson's defaults; "shade" defaults to "normal",
// "color" is required for "flat"). Unknown keys, wrong types, non-finite
// numbers and invalid spheres are errors naming the JSON path
// ("spheres[3].radius"). The camera and sky are checked by validate() after a
// caller has applied its overrides (the CLI's options); path() of its error
// is the JSON path too.
#pragma once
#include <string>
#include <string_view>
#include <variant>

#include "scene/scene.h"

namespace raycast {

struct scene_file_error {
  std::string path;     // "camera.vfov", "spheres[3].radius"; empty for the whole file
  std::string message;  // why
};

// Parses the text of a scene file and validates its spheres. As on the command line, a
// "vup" without "lookat" looks down -z from "lookfrom".
std::variant<scene_params, scene_file_error> parse_scene_file(std::string_view text);

}  // namespace raycast
