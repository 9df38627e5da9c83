// The built-in scenes `--scene NAME` names: the book's chapters 4-6, and
// the world lit.
#pragma once
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "scene/sphere.h"

namespace raycast {

// "sky" (the lesson, chapter 4; no spheres, the default), "red-sphere" (ch. 5:
// sphere (0,0,-1) r 0.5, flat red), "normals" (ch. 6: that sphere shaded
// 0.5 (N + 1)), "world" (ch. 6's end: that sphere and the ground sphere
// (0,-100.5,-1) r 100, both normal-shaded), "lit-world" (that world under
// a headlight: an orange sphere on a grey ground). The one list of them:
// messages, --help and the Python docstrings are built from it.
std::span<const std::string_view> builtin_scene_names();

// The spheres of a built-in scene; nullopt for a name that is not one.
std::optional<std::vector<sphere>> builtin_spheres(std::string_view name);

// The names, comma-separated, for messages.
std::string builtin_scene_list();

}  // namespace raycast
