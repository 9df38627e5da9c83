// raycast as a library: describe a scene, render it into memory or to a file
// with the command line's options. Self-contained (the standard library
// only); link raycast::raycast (find_package(raycast CONFIG)).
//
//   raycast::api::scene s = raycast::api::builtin_scene("world");
//   s.cam.width = 320;
//   raycast::api::image img = raycast::api::render(s, {});   // 320 x 180 RGB8
//   raycast::api::render_to_file(s, {.samples = 16}, "world.png");
//
// Errors throw raycast::api::error (nothing is printed): field() names the
// input as a scene file or the command line's long option would ("camera.vfov",
// "spheres[3].radius", "threads", "path"), kind() says what went wrong.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace raycast::api {

using vec3 = std::array<double, 3>;

enum class shading : uint8_t {
  normal,  // 0.5 (N + 1), N the unit normal facing the ray
  flat,    // the sphere's colour wherever it is hit
  lit,     // the sphere's colour under a headlight (where this build has it)
};

// perspective: rays from lookfrom through the viewport (the book's camera);
// orthographic: parallel rays along the view direction from an image plane
// through lookfrom, viewport_height high (vfov and focal_length mean nothing).
enum class projection : uint8_t { perspective, orthographic };

// The command line's camera options, and their defaults.
struct camera {
  enum projection projection = projection::perspective;
  double aspect = 16.0 / 9.0;
  int64_t width = 400;
  std::optional<int64_t> height;  // default: int(width / aspect), at least 1
  double viewport_height = 2.0;
  double focal_length = 1.0;
  vec3 lookfrom{0.0, 0.0, 0.0};
  std::optional<vec3> lookat;  // without it: straight down -z, +y up (vup unused)
  vec3 vup{0.0, 1.0, 0.0};
  std::optional<double> vfov;  // degrees, in (0, 180); replaces viewport_height
};

struct sky {
  vec3 bottom{1.0, 1.0, 1.0};
  vec3 top{0.5, 0.7, 1.0};
};

// How lit spheres are lit: colour (0.2 A + 0.8 max(0, N . L) S), L toward
// the light (without a direction, the camera: a headlight), S 0 where a
// sphere shadows the hit (shadows), A the fraction of ao_samples
// cosine-weighted rays about N that meet no sphere within ao_distance.
struct light {
  std::optional<vec3> direction;  // toward the light; any length but 0
  bool shadows = false;           // needs a direction
  uint32_t ao_samples = 0;        // 0 to 4096; 0: no ambient occlusion
  double ao_distance = std::numeric_limits<double>::infinity();  // above 0; default unbounded
};
struct sphere {
  vec3 center{0.0, 0.0, 0.0};
  double radius = 1.0;
  shading shade = shading::normal;
  vec3 color{1.0, 0.0, 0.0};  // for flat (and lit)
};

// Spheres in the caller's arrays, read in place: nothing is copied (but for
// the reference backend, which makes a vector). They must stay alive and
// unchanged while render() / render_to_file() / a job's constructor runs.
// Strides are in bytes; 0 means packed (3 elements a row, 1 for radii).
struct sphere_arrays {
  static constexpr std::ptrdiff_t one_for_all = std::numeric_limits<std::ptrdiff_t>::min();
  enum class element : uint8_t { f32, f64, u8 };  // u8: 0-255, read as value / 255 (colours)
  struct column {
    const void* data = nullptr;
    element type = element::f64;
    std::ptrdiff_t stride = 0;            // from one sphere to the next; 0: packed; one_for_all:
                                          // every sphere reads the value at data (a radius for all)
    std::ptrdiff_t component_stride = 0;  // from x to y to z (r g b)
    bool byte_swapped = false;            // numbers in the other byte order (big-endian data here)
  };
  size_t count = 0;
  column centers;  // count x 3
  column radii;    // count
  column colors;   // count x 3; data null: normal shading only (flat and lit
                   // spheres show their colours and need them, as a scene file's)
  shading shade = shading::normal;  // all spheres', unless shades is set
  const shading* shades = nullptr;  // one per sphere
  // Keeps the arrays alive where the scene owns them (load_scene's particle
  // file); null for a caller's arrays.
  std::shared_ptr<const void> owner;
};

struct scene {
  camera cam;
  struct sky sky;
  std::vector<sphere> spheres;
  std::optional<sphere_arrays> arrays;  // instead of spheres, when set
  struct light light;
};

// A built-in scene by name, as the command line's --scene NAME; the names
// are builtin_scene_names()'s.
scene builtin_scene(const std::string& name);
std::vector<std::string> builtin_scene_names();
// How a particle file's vertices become spheres: the command line's
// --radius, --color-by, --colormap and --color-range.
struct particles {
  std::optional<double> radius;  // every sphere's (instead of the file's radius property)
  std::string color_by;          // a vertex property shown through the colormap; empty: none
  std::string colormap;                              // viridis (empty: the default), magma, gray
  std::optional<std::array<double, 2>> color_range;  // lo < hi; default: the property's min and max
};

// A scene file (the command line's --scene FILE.json) or its text, or a
// particle file (FILE.ply: its spheres are read in place, kept alive by
// arrays->owner). Errors name the JSON path ("spheres[3].radius") with where
// in the text it is, or the PLY file's part ("vertex[3].radius") and byte.
scene load_scene(const std::string& path, const particles& p = {});
scene parse_scene(const std::string& json_text);

enum class pixel_type : uint8_t {
  rgb8,     // 3 bytes a pixel
  rgb_f32,  // 3 floats a pixel, linear colour
};

struct region {
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // columns [x0, x1), rows [y0, y1); row 0 at the top
};

// The command line's options, with its names and defaults.
struct options {
  std::string backend = "auto";     // auto, reference, scalar, sse2, avx2, avx512, neon
  std::string precision = "exact";  // exact, fast
  int threads = 0;                  // 0: all cores; else 1 to 1024
  int64_t samples = 1;              // 1 to 2^20
  std::string sampler = "sobol";    // random, stratified, sobol
  uint64_t seed = 0;
  std::optional<struct region> region;  // the whole image unless set
  pixel_type pixels = pixel_type::rgb8;  // render() only; a file takes its format's
  std::string format;  // render_to_file(): png, ppm, jpg, tif, exr; empty: by the extension
};

// Rows top first, each width * 3 values, packed.
struct image {
  int64_t width = 0, height = 0;
  pixel_type pixels = pixel_type::rgb8;
  std::vector<unsigned char> data;
  size_t stride() const { return size_t(width) * (pixels == pixel_type::rgb8 ? 3 : 12); }
};

class error : public std::runtime_error {
 public:
  enum class kind : uint8_t {
    invalid_argument,     // a scene or option value; field() names it
    unsupported_backend,  // this CPU or build cannot run the backend asked for
    io,                   // reading a scene file, writing an image
  };
  error(enum kind k, std::string field, std::string message);
  enum kind kind() const { return kind_; }
  const std::string& field() const { return field_; }      // "" for a whole file
  const std::string& message() const { return message_; }  // why; what() is "field: message"

 private:
  enum kind kind_;
  std::string field_, message_;
};

// A validated, prepared render: the scene's spheres are read (and, for
// arrays, no longer needed) when it is constructed.
class job {
 public:
  job(const scene& s, const options& o);
  ~job();
  job(job&&) noexcept;
  job& operator=(job&&) noexcept;

  int64_t width() const;   // of the output: the region's
  int64_t height() const;
  std::string backend() const;  // the one it renders with ("auto" resolved)

  // Fills width() x height() pixels at data, row r at data + r * stride.
  // Thread-safe for different buffers; prints nothing.
  void render_into(void* data, size_t stride, pixel_type pixels) const;
  image render(pixel_type pixels) const;
  // Renders and writes in bands (memory: one band), through a temporary file
  // renamed into place: an error leaves the destination as it was. Path "-"
  // is standard output (a binary PPM), as the command line's -o -.
  void write(const std::string& path, const std::string& format = "") const;

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

image render(const scene& s, const options& o = {});
void render_to_file(const scene& s, const options& o, const std::string& path);

// Writes an image (from render()) the way render_to_file() does: format from
// the extension unless given; PNG, JPEG, TIFF and EXR need the image module
// installed beside the library (lib/raycast/raycast_oiio.so).
void write(const std::string& path, const image& img, const std::string& format = "");
// The same for pixels in the caller's memory (rows top first).
void write(const std::string& path, const void* data, size_t stride, int64_t width, int64_t height,
           pixel_type pixels, const std::string& format = "");

}  // namespace raycast::api
