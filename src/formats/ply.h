// Particle files (`--scene FILE.ply`): spheres from the PLY format that
// point-cloud and particle tools write (Open3D, PCL, CloudCompare, MeshLab,
// Blender, OVITO). Its layout and the reader's contract are in README.md
// ("Particle files"); in short:
//
//   ply
//   format binary_little_endian 1.0      (or binary_big_endian, ascii)
//   element vertex 1000000
//   property float x                     (x y z: float or double, required)
//   property float y
//   property float z
//   property float radius                (float or double; optional with --radius)
//   property uchar red                   (red green blue: uchar 0-255 or
//   property uchar green                  float/double 0-1; optional)
//   property uchar blue
//   end_header
//
// The vertex element gives one sphere per vertex; other elements (faces) are
// skipped. A binary body is read once into memory of the file's own layout
// and the spheres are read from it in place (sphere arrays' columns with the
// file's strides, byte-swapped where the file's order is not the machine's):
// nothing is converted or copied again until the float renderers prepare
// their arrays. An ASCII body is parsed into doubles, rounded to each
// property's declared type. Spheres with colours (the file's, or
// --color-by's) are lit; without, shaded by their normals.
//
// Every refusal names where: the path is "header", "vertex", "vertex.NAME"
// or "vertex[K].NAME" and the message ends with the file's byte offset
// "(at byte N)". Memory stays bounded by the file's size: a count that
// promises more than the file can hold is refused before anything is
// allocated for it.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "formats/format.h"
#include "formats/json.h"
#include "raycast/description.h"

namespace raycast {

// The longest header read (comments included): a header that never ends is
// refused after this many bytes.
inline constexpr size_t max_ply_header_bytes = size_t(1) << 20;

// Where a PLY file's bytes come from: its size when opened, a reader of
// bytes at an offset (fewer only at the end; -1 on a failure, errno set),
// and whether the file is still as it was opened (called after the read).
struct byte_source {
  uint64_t size = 0;
  std::function<ptrdiff_t(uint64_t offset, size_t n, char* to)> read;
  std::function<bool()> unchanged;
};

// Bytes in memory as a source (the tests', the fuzzer's, a caller's
// buffer): they must outlive the read; unchanged is true.
byte_source memory_source(std::string_view bytes);

// The vertices as a frame of particle data: x y z, radius and red green
// blue in their roles where given, every other property by its name.
// Throws formats::format_error, its message the path and why ("vertex[3].x:
// nan is not a finite number (at byte 212)").
particle_frame read_ply_frame(const byte_source& source);
// The same made spheres as the options ask (particles/spheres.h), the
// refusal's path the reader's or the option's keyword.
std::variant<scene_file_contents, scene_file_error> read_ply(const byte_source& source, const api::particles& o);
// The file's format: one frame, its vertices.
const formats::format& ply_format();

// The file at path, opened as a JSON scene file is (regular files only); its
// read errors have io set.
std::variant<scene_file_contents, scene_file_error> read_ply_file(const std::string& path, const api::particles& o);

}  // namespace raycast
