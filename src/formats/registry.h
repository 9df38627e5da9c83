// The one place that decides what a --scene value names: a built-in scene,
// or a file, whose format is told by its content where the format defines a
// signature (PLY's "ply", JSON's '{') and by its name otherwise; the file
// goes to that format's reader. Nothing else knows a format's name.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "formats/json.h"
#include "raycast/description.h"

namespace raycast::formats {

// A scene file format: its name, the extensions it is known by (lower case,
// with the dot) and whether a file's first bytes are its.
struct scene_format {
  std::string_view name;  // "json", "ply"
  std::span<const std::string_view> extensions;
  bool (*sniff)(std::string_view head);
  // Reads the whole file: its spheres (or particle arrays) and its scene keys.
  std::variant<scene_file_contents, scene_file_error> (*read)(const std::string& path, const api::particles& p);
};

std::span<const scene_format> scene_formats();

// The format of the file at path (its first bytes read; a file that cannot
// be opened is told by its name), or null: neither its content nor its
// name is a format's.
const scene_format* detect(const std::string& path);

// Whether name is a file name a format is known by (it ends in one of their
// extensions, any case), so that read_scene takes it for a file.
bool is_scene_file_name(std::string_view name);
bool is_particle_file_name(std::string_view name);

// The command line's --scene: a built-in scene's name (its spheres), or a
// file read by its format's reader with the particle options given (only
// particle formats use them: the caller refuses them for others); another
// name is an error listing the built-in ones (and the nearest, when it
// looks like a slip). A file's error is its reader's: the caller names the
// file.
std::variant<scene_file_contents, scene_file_error> read_scene(const std::string& name_or_path,
                                                               const api::particles& particles = {});

}  // namespace raycast::formats
