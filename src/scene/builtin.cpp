#include "scene/builtin.h"

#include <array>
#include <string>

namespace raycast {

namespace {
constexpr std::array<std::string_view, 5> names = {"sky", "red-sphere", "normals", "world", "lit-world"};
}  // namespace

std::span<const std::string_view> builtin_scene_names() { return names; }

std::optional<std::vector<sphere>> builtin_spheres(std::string_view name) {
  const sphere small{{0.0, 0.0, -1.0}, 0.5, shading::normal};
  if (name == "sky") return std::vector<sphere>{};
  if (name == "red-sphere") {
    sphere red = small;
    red.shade = shading::flat;
    red.color = {1.0, 0.0, 0.0};
    return std::vector<sphere>{red};
  }
  if (name == "normals") return std::vector<sphere>{small};
  if (name == "world") return std::vector<sphere>{small, {{0.0, -100.5, -1.0}, 100.0, shading::normal}};
  if (name == "lit-world")  // the world under a headlight: an orange sphere on a grey ground
    return std::vector<sphere>{{{0.0, 0.0, -1.0}, 0.5, shading::lit, {1.0, 0.55, 0.1}},
                               {{0.0, -100.5, -1.0}, 100.0, shading::lit, {0.7, 0.7, 0.7}}};
  return std::nullopt;
}

std::string builtin_scene_list() {
  std::string s;
  for (std::string_view n : names) {
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

}  // namespace raycast
