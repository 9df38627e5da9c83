#include "formats/registry.h"

#include <algorithm>
#include <cctype>

#include "formats/ply.h"
#include "formats/regular_file.h"
#include "scene/builtin.h"
#include "text/names.h"

namespace raycast::formats {
namespace {

constexpr std::string_view json_extensions[] = {".json"};
constexpr std::string_view ply_extensions[] = {".ply"};

bool json_sniff(std::string_view head) {
  const size_t k = head.find_first_not_of(" \t\r\n");
  return k != std::string_view::npos && head[k] == '{';
}
bool ply_sniff(std::string_view head) { return head.starts_with("ply\n") || head.starts_with("ply\r\n"); }

std::variant<scene_file_contents, scene_file_error> read_json(const std::string& path, const api::particles&) {
  return read_scene_file(path);
}

constexpr scene_format known[] = {
    {"json", json_extensions, json_sniff, read_json},
    {"ply", ply_extensions, ply_sniff, read_ply_file},
};

bool ends_with(std::string_view name, std::string_view ext) {
  if (name.size() <= ext.size()) return false;  // ".ply" alone is a name, not an extension
  const std::string_view tail = name.substr(name.size() - ext.size());
  return std::equal(tail.begin(), tail.end(), ext.begin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == b; });
}

const scene_format* by_name(std::string_view name) {
  for (const scene_format& f : known)
    for (std::string_view ext : f.extensions)
      if (ends_with(name, ext)) return &f;
  return nullptr;
}

}  // namespace

std::span<const scene_format> scene_formats() { return known; }

const scene_format* detect(const std::string& path) {
  const scene_format* named = by_name(path);
  auto opened = regular_file::open(path);
  if (auto* f = std::get_if<std::unique_ptr<regular_file>>(&opened)) {
    char head[4096];
    const ptrdiff_t got = (*f)->read_at(0, sizeof head, head);
    if (got > 0)
      for (const scene_format& fmt : known)
        if (fmt.sniff(std::string_view(head, size_t(got)))) return &fmt;
  }
  return named;
}

bool is_scene_file_name(std::string_view name) { return by_name(name) != nullptr; }
bool is_particle_file_name(std::string_view name) {
  const scene_format* f = by_name(name);
  return f && f->name != "json";
}

std::variant<scene_file_contents, scene_file_error> read_scene(const std::string& name_or_path,
                                                               const api::particles& particles) {
  if (auto spheres = builtin_spheres(name_or_path)) {
    scene_file_contents c;
    c.scene.spheres = std::move(*spheres);
    return c;
  }
  const scene_format* f = is_scene_file_name(name_or_path) ? detect(name_or_path) : nullptr;
  if (!f)
    return scene_file_error{"", not_one_of(name_or_path, quote_token(name_or_path), builtin_scene_names(),
                                           ", a .json scene file or a .ply particle file")};
  return f->read(name_or_path, particles);
}

}  // namespace raycast::formats
