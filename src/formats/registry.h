// The one place that decides what a --scene value names: a built-in scene,
// or a file, whose format is told by its content where the format defines a
// signature (PLY's "ply", GSD's magic, a LAMMPS dump's "ITEM: TIMESTEP",
// JSON's '{') and by its name otherwise; the file goes to that format's
// reader. Nothing else knows a format's name.
#pragma once
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "formats/format.h"
#include "formats/json.h"

namespace raycast::formats {

// A scene file format (JSON): read whole, its spheres and its scene keys.
struct scene_format {
  std::string_view name;
  std::span<const std::string_view> extensions;
  bool (*sniff)(std::string_view head);
  std::variant<scene_file_contents, scene_file_error> (*read)(const std::string& path);
};

std::span<const scene_format* const> scene_formats();
std::span<const format* const> particle_formats();  // PLY, LAMMPS dumps, extended XYZ, GSD

// A file's format: a scene format or a particle format, or neither (null both).
struct detected {
  const scene_format* scene = nullptr;
  const format* particles = nullptr;
  explicit operator bool() const { return scene || particles; }
};

// The format of the file at path: by the first bytes of its content (a .gz
// file's decompressed) where they are a format's, else by its name (a file
// that cannot be opened is told by its name alone).
detected detect(const std::string& path);

// What --scene's value names, before anything is read: a built-in scene, or
// a file (a name a format is known by, or a file that exists).
bool is_builtin_name(std::string_view name);
bool names_a_file(const std::string& name);

}  // namespace raycast::formats
