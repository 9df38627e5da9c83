// What one render needs: the camera, the sky it looks at and the spheres in
// front of the sky (none: the lesson's picture). A job builds its
// scene_params, validates them once here, and renders the scene they make.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include "scene/camera.h"
#include "scene/invalid.h"
#include "scene/light.h"
#include "scene/sky.h"
#include "scene/sphere.h"

namespace raycast {

// Spheres in a caller's arrays, read in place (no copy): a library user's
// NumPy arrays or std::vector<float>s. Each array is float or double; byte
// strides between spheres and between components (xyz, rgb) let any strided
// layout through. Not owned: the arrays must outlive the renderer's
// construction (the reference backend copies them then, the others prepare
// their float scene from them).
struct sphere_view {
  // f32, f64: numbers; u8: 0-255 read as value / 255 (8-bit colours).
  enum class element : uint8_t { f32, f64, u8 };
  struct column {
    const void* data = nullptr;
    element type = element::f64;
    ptrdiff_t stride = 0;            // bytes from one sphere to the next (0: one value for all)
    ptrdiff_t component_stride = 0;  // bytes from x to y to z (r g b); unused for radii
    bool swapped = false;            // bytes in the other order (a big-endian file here)

    double get(size_t k, int c = 0) const {
      const auto* p = static_cast<const unsigned char*>(data) + ptrdiff_t(k) * stride + c * component_stride;
      switch (type) {
        case element::u8: return double(*p) / 255.0;
        case element::f32: {
          uint32_t b;
          std::memcpy(&b, p, sizeof b);
          return std::bit_cast<float>(swapped ? __builtin_bswap32(b) : b);
        }
        case element::f64: break;
      }
      uint64_t b;
      std::memcpy(&b, p, sizeof b);
      return std::bit_cast<double>(swapped ? __builtin_bswap64(b) : b);
    }
  };
  size_t count = 0;
  column centers;             // N x 3
  column radii;               // N
  column colors;              // N x 3; data null: none (normal shading only)
  shading shade = shading::normal;   // every sphere's, unless shades is set
  const shading* shades = nullptr;   // N, one per sphere
  // Keeps the arrays' memory alive where the view owns it (a particle file
  // read by formats/ply.h); null for a caller's arrays.
  std::shared_ptr<const void> owner;

  sphere at(size_t k) const {
    sphere s;
    s.center = point3(centers.get(k, 0), centers.get(k, 1), centers.get(k, 2));
    s.radius = radii.get(k);
    s.shade = shades ? shades[k] : shade;
    if (colors.data) s.flat_color = color(colors.get(k, 0), colors.get(k, 1), colors.get(k, 2));
    return s;
  }
};

struct scene {
  camera cam;
  raycast::sky sky;
  std::vector<sphere> spheres;  // empty: the sky alone, today's kernel
  // Instead of `spheres`, when set: spheres read from a caller's arrays.
  std::optional<sphere_view> arrays = std::nullopt;
  lighting light;  // scene/light.h: the headlight unless set

  size_t sphere_count() const { return arrays ? arrays->count : spheres.size(); }
  sphere sphere_at(size_t k) const { return arrays ? arrays->at(k) : spheres[k]; }
};

// The spheres as a vector: a copy of the arrays' (the double reference reads
// a vector), or of `spheres`.
std::vector<sphere> sphere_vector(const scene& s);

// A scene as a caller describes it, before validation.
struct scene_params {
  camera_params camera;
  raycast::sky sky;
  std::vector<sphere> spheres;
  std::optional<sphere_view> arrays = std::nullopt;  // instead of spheres, when set
  lighting light;
};

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
// the lighting,
// the sphere count (at most max_spheres), each sphere and its centre within
// max_sphere_extent of the camera.
std::optional<invalid_field> validate(const scene_params& p);

// The scene; p must pass validate(). The second moves the spheres (a scene
// file's millions) instead of copying them.
scene make_scene(const scene_params& p);
scene make_scene(scene_params&& p);

}  // namespace raycast
