// What one render needs, built from its description (api::scene): the
// camera's frame, the sky's colours, the light and the spheres in front of
// the sky (none: the lesson's picture). A job validates the description once
// here and renders the scene it makes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "raycast/description.h"
#include "scene/camera.h"
#include "scene/invalid.h"
#include "scene/light.h"
#include "scene/sky.h"
#include "scene/sphere.h"

namespace raycast {

struct scene {
  camera cam;
  raycast::sky sky;
  std::vector<sphere> spheres;  // empty: the sky alone
  // Instead of `spheres`, when set: spheres read from memory the scene does not own.
  std::optional<api::sphere_arrays> arrays = std::nullopt;
  api::light light;  // the headlight unless set

  size_t sphere_count() const { return arrays ? arrays->count : spheres.size(); }
  sphere sphere_at(size_t k) const { return arrays ? arrays->at(k) : spheres[k]; }
};

// The spheres as a vector: a copy of the arrays' (the double reference reads
// a vector), or of `spheres`.
std::vector<sphere> sphere_vector(const scene& s);

// The largest sphere radius, and the largest distance from the camera
// (lookfrom) to a sphere's centre in any coordinate. The float renderers scale
// each sphere by a power of two 2^e with max(|lookfrom - center| components,
// radius) < 2^e and need 2^e <= 2^126 (1e37 < 2^123, with room for the ray's
// own terms); beyond it a sphere would silently vanish.
inline constexpr double max_sphere_extent = 1e37;

// The most spheres a scene holds: the float renderers index them with 32 bits
// (the culling lists, the row order), so a larger count is refused, not cut.
inline constexpr size_t max_spheres = 0xffffffffu;

// Why a sphere cannot be rendered (a non-finite centre, a radius not positive
// and finite or above max_sphere_extent, a flat colour not finite within
// +-1e30), or nullopt.
std::optional<invalid_field> validate(const sphere& s, size_t index);

// The first field that cannot make a scene, or nullopt: the camera, the sky,
// the lighting, the sphere count (at most max_spheres), each sphere and its
// centre within max_sphere_extent of the camera.
std::optional<invalid_field> validate(const api::scene& d);

// The scene; d must pass validate(). The second moves the spheres (a scene
// file's millions) instead of copying them.
scene make_scene(const api::scene& d);
scene make_scene(api::scene&& d);

}  // namespace raycast
