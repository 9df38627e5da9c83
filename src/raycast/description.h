// What a render is, as plain data: the scene (camera, sky, light, spheres)
// and how to render it (options). The one model of a render: the command
// line, scene and particle files, Python and C++ callers all fill these
// structs (src/settings/ resolves the text front ends' settings into them),
// and a job checks them and renders them (raycast/raycast.h). Standard
// library only; every default is the command line's.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace raycast::api {

// x, y, z. Built from three numbers or from any vector type with members x,
// y and z (GLM's, for one). The header asks for C++17 only.
struct vec3 {
  double x = 0, y = 0, z = 0;
  constexpr vec3() = default;
  constexpr vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  template <class V, class = std::enable_if_t<!std::is_same_v<V, vec3>>,
            class = decltype(double(std::declval<const V&>().x) + double(std::declval<const V&>().y) +
                             double(std::declval<const V&>().z))>
  constexpr vec3(const V& v) : x(double(v.x)), y(double(v.y)), z(double(v.z)) {}
  constexpr double operator[](size_t k) const { return k == 0 ? x : k == 1 ? y : z; }
  constexpr double& operator[](size_t k) { return k == 0 ? x : k == 1 ? y : z; }
  friend constexpr bool operator==(const vec3& a, const vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
  friend constexpr bool operator!=(const vec3& a, const vec3& b) { return !(a == b); }
};

enum class shading : uint8_t {
  normal,  // 0.5 (N + 1) per channel, N the unit normal facing the ray (the book's ch. 6)
  flat,    // the sphere's colour wherever it is hit (ch. 5's red sphere)
  lit,     // the sphere's colour under the light (light, below)
};

// perspective: rays from lookfrom through the viewport (the book's camera);
// orthographic: parallel rays along the view direction from an image plane
// through lookfrom, viewport_height high (vfov and focal_length mean nothing).
enum class projection : uint8_t { perspective, orthographic };

struct camera {
  enum projection projection = projection::perspective;
  double aspect = 16.0 / 9.0;
  int64_t width = 400;
  std::optional<int64_t> height;  // default: int(width / aspect), at least 1
  double viewport_height = 2.0;
  double focal_length = 1.0;
  vec3 lookfrom{0.0, 0.0, 0.0};
  std::optional<vec3> lookat;  // without it: straight down -z, +y up (the lesson's; vup unused)
  vec3 vup{0.0, 1.0, 0.0};
  std::optional<double> vfov;  // degrees, in (0, 180); replaces viewport_height by 2 tan(vfov / 2) focal_length
};

struct sky {
  vec3 bottom{1.0, 1.0, 1.0};  // seen looking straight down
  vec3 top{0.5, 0.7, 1.0};     // seen looking straight up
};

// How lit spheres are lit: colour (0.2 A + 0.8 max(0, N . L) S), L toward
// the light (without a direction, the camera: a headlight), S 0 where a
// sphere shadows the hit (shadows), A the fraction of ao_samples
// cosine-weighted rays about N that meet no sphere within ao_distance.
struct light {
  std::optional<vec3> direction;  // toward the light; any length but 0
  bool shadows = false;           // needs a direction
  uint32_t ao_samples = 0;        // 0 to 4096; 0: no ambient occlusion
  double ao_distance = std::numeric_limits<double>::infinity();  // above 0

  bool secondary() const { return shadows || ao_samples > 0; }  // any shadow or AO ray cast
  bool any() const { return direction.has_value() || secondary(); }  // more than the headlight
};

struct sphere {
  vec3 center{0.0, 0.0, 0.0};
  double radius = 1.0;
  shading shade = shading::normal;
  vec3 color{1.0, 0.0, 0.0};  // what flat and lit spheres show
};

// One value (or x, y, z; r, g, b) per row of a caller's or a file's memory,
// read in place. Strides are bytes, as NumPy's: stride 0 gives every row the
// first row's value.
enum class element : uint8_t {
  f32,
  f64,
  u8,   // read as value / 255 (8-bit colours)
  u32,  // whole numbers: particle types
  i32,
};
struct column {
  const void* data = nullptr;
  element type = element::f64;
  std::ptrdiff_t stride = 0;            // from one row to the next
  std::ptrdiff_t component_stride = 0;  // from x to y to z (r g b); unused for one value a row
  bool byte_swapped = false;            // numbers in the other byte order (big-endian data here)

  // Row k's component c.
  double get(size_t k, int c = 0) const {
    const auto* p = static_cast<const unsigned char*>(data) + std::ptrdiff_t(k) * stride + c * component_stride;
    switch (type) {
      case element::u8: return double(*p) / 255.0;
      case element::f32: return double(load<float, uint32_t>(p));
      case element::u32: return double(load<uint32_t, uint32_t>(p));
      case element::i32: return double(load<int32_t, uint32_t>(p));
      case element::f64: break;
    }
    return load<double, uint64_t>(p);
  }

 private:
  // A T from its bytes at p, swapped where the column says so.
  template <class T, class Bits>
  T load(const unsigned char* p) const {
    Bits b;
    std::memcpy(&b, p, sizeof b);
    if (byte_swapped) {
      if constexpr (sizeof(Bits) == 4) b = __builtin_bswap32(b);
      else b = __builtin_bswap64(b);
    }
    T t;
    std::memcpy(&t, &b, sizeof t);
    return t;
  }
};

// Rows of `components` packed values of T (float, double, uint8_t, ...).
template <class T>
column packed(const T* data, int components = 1) {
  static_assert(sizeof(T) == 1 || sizeof(T) == 4 || sizeof(T) == 8);
  constexpr element type = std::is_same_v<T, float>      ? element::f32
                           : std::is_same_v<T, double>   ? element::f64
                           : std::is_same_v<T, uint8_t>  ? element::u8
                           : std::is_same_v<T, uint32_t> ? element::u32
                                                         : element::i32;
  return {data, type, std::ptrdiff_t(sizeof(T)) * components, std::ptrdiff_t(sizeof(T))};
}

// Spheres in memory the scene does not own (a caller's arrays, a file's
// body), read in place: nothing is copied until a job prepares its own
// float arrays. They must stay alive and unchanged while a job is built.
struct sphere_arrays {
  size_t count = 0;
  column centers;  // count x 3
  column radii;    // count
  column colors;   // count x 3; data null: none (normal shading only: flat
                   // and lit spheres show their colours and need them)
  shading shade = shading::normal;  // every sphere's, unless shades is set
  const shading* shades = nullptr;  // one per sphere
  std::shared_ptr<const void> owner;  // keeps the memory alive where the scene owns it

  sphere at(size_t k) const {
    sphere s;
    s.center = {centers.get(k, 0), centers.get(k, 1), centers.get(k, 2)};
    s.radius = radii.get(k);
    s.shade = shades ? shades[k] : shade;
    if (colors.data) s.color = {colors.get(k, 0), colors.get(k, 1), colors.get(k, 2)};
    return s;
  }
};

struct scene {
  struct camera cam;
  struct sky sky;
  std::vector<sphere> spheres;
  std::optional<sphere_arrays> arrays;  // instead of spheres, when set
  struct light light;

  size_t sphere_count() const { return arrays ? arrays->count : spheres.size(); }
  sphere sphere_at(size_t k) const { return arrays ? arrays->at(k) : spheres[k]; }
};

// How particle data (a LAMMPS dump's, an extended XYZ or GSD file's, a PLY
// file's vertices) become spheres. A type is named as the file names it: an
// element ("Cu"), a GSD type ("A"), a LAMMPS type number ("1").
struct particles {
  std::optional<double> radius;  // every sphere's, instead of the file's radii or its types'
  std::vector<std::pair<std::string, double>> type_radius;  // a type's radius (else its element's, else 0.5)
  std::vector<std::pair<std::string, vec3>> type_color;     // a type's colour, in [0, 1]
  // "type" (a palette by type), "element" (Jmol's colours), or a property
  // shown through the colormap; empty: the file's colours, else its types'.
  std::string color_by;
  std::string colormap;  // viridis (empty: the default), magma, plasma, inferno, cividis, coolwarm, gray
  std::optional<std::array<double, 2>> color_range;  // lo < hi; default: the property's min and max
  bool range_in_percentiles = false;  // color_range as percentiles of the frame's values: 1, 99
  std::optional<shading> shade;  // every sphere's; default: lit where the file gives colours or types
  // Where a particle file is seen from when no camera is given: "corner"
  // (the default), "x", "y" or "z" (along that axis); the picture holds its
  // simulation box (else its particles' bounds) whole.
  std::string view;
};

// Columns [x0, x1), rows [y0, y1) of the image, row 0 at the top.
struct region {
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int64_t width() const { return x1 - x0; }
  int64_t height() const { return y1 - y0; }
  friend bool operator==(const region& a, const region& b) {
    return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1;
  }
};

enum class pixel_type : uint8_t {
  rgb8,     // 3 bytes a pixel
  rgb_f32,  // 3 floats a pixel, linear colour
};

// How to render, with the command line's names and defaults.
struct options {
  std::string backend = "auto";     // auto, reference, scalar, sse2, avx2, avx512, neon
  std::string precision = "exact";  // exact, fast (the sky alone: spheres are always exact)
  int threads = 0;                  // 0: all cores; else 1 to 1024
  int64_t samples = 1;              // 1 to 2^20
  std::string sampler = "sobol";    // random, stratified, sobol
  uint64_t seed = 0;
  std::optional<struct region> region;   // the whole image unless set
  pixel_type pixels = pixel_type::rgb8;  // render() only; a file takes its format's
  std::string format;  // render_to_file(): png, ppm, jpg, tif, exr; empty: by the extension
};

}  // namespace raycast::api
