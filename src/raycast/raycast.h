// raycast as a library: describe a scene, render it into memory or to a file
// with the command line's options. Self-contained (the standard library
// only); link raycast::raycast (find_package(raycast CONFIG)).
//
//   raycast::api::scene s = raycast::api::builtin_scene("world");
//   s.cam.width = 320;
//   raycast::api::image img = raycast::api::render(s, {});   // 320 x 180 RGB8
//   raycast::api::render_to_file(s, {.samples = 16}, "world.png");
//
// The description's types (scene, camera, sky, light, sphere arrays,
// options) are raycast/description.h's. Errors throw raycast::api::error
// (nothing is printed): field() names the input as a scene file or the
// command line's long option would ("camera.vfov", "spheres[3].radius",
// "threads", "path"), kind() says what went wrong.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "raycast/description.h"

namespace raycast::api {

// A built-in scene by name, as the command line's --scene NAME; the names
// are builtin_scene_names()'s.
scene builtin_scene(const std::string& name);
std::vector<std::string> builtin_scene_names();
// A scene file (the command line's --scene FILE.json) or its text, or a
// particle file (FILE.ply: its spheres are read in place, kept alive by
// arrays->owner). Errors name the JSON path ("spheres[3].radius") with where
// in the text it is, or the PLY file's part ("vertex[3].radius") and byte.
scene load_scene(const std::string& path, const particles& p = {});
scene parse_scene(const std::string& json_text);

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
  job(scene&& s, const options& o);  // moves the spheres (a scene file's millions)
  ~job();
  job(job&&) noexcept;
  job& operator=(job&&) noexcept;

  int64_t width() const;   // of the output: the region's
  int64_t height() const;
  std::string backend() const;  // the one it renders with ("auto" resolved)

  // What its preparation built and what a render casts, for --stats.
  struct stats {
    double light_seconds = 0;  // of the construction: the shadow and AO rays' structures
    size_t light_bytes = 0;
    uint32_t samples = 1;      // per pixel
    size_t spheres = 0;
    // Of the renders so far: the seen spheres' near-field lists gathered, the
    // threads' seconds gathering them, and the bytes they hold.
    size_t light_lists = 0;
    double list_seconds = 0;
    size_t list_bytes = 0;
  };
  stats statistics() const;

  // Fills width() x height() pixels at data, row r at data + r * stride.
  // Thread-safe for different buffers; prints nothing.
  void render_into(void* data, size_t stride, pixel_type pixels) const;
  image render(pixel_type pixels) const;
  // Renders and writes in bands (memory: one band), through a temporary file
  // renamed into place: an error leaves the destination as it was. Path "-"
  // is standard output (a binary PPM), as the command line's -o -. progress
  // is called before each band is rendered ("rendering") and written
  // ("writing") with the rows done so far. Returns the seconds each part took.
  struct timings {
    double open = 0;    // opening the output: the image library loaded where the format needs it
    double render = 0;
    double write = 0;   // encoding and writing, and the rename into place
  };
  using progress_fn = std::function<void(int64_t rows_done, const char* phase)>;
  timings write(const std::string& path, const std::string& format = "", const progress_fn& progress = {}) const;

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
