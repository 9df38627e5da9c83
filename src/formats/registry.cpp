#include "formats/registry.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>

#include "formats/gsd/hoomd.h"
#include "formats/input/text_source.h"
#include "formats/lammps/lammps_dump.h"
#include "formats/ply.h"
#include "formats/xyz/extxyz.h"
#include "formats/regular_file.h"
#include "scene/builtin.h"

namespace raycast::formats {
namespace {

constexpr std::string_view json_extensions[] = {".json"};

bool json_sniff(std::string_view head) {
  const size_t k = head.find_first_not_of(" \t\r\n");
  return k != std::string_view::npos && head[k] == '{';
}

constexpr scene_format json{"json", json_extensions, json_sniff, read_scene_file};
constexpr const scene_format* scene_list[] = {&json};

const std::vector<const format*>& particle_list() {
  static const std::vector<const format*> list = {&ply_format(), &gsd_format(), &lammps_dump_format(), &xyz_format()};
  return list;
}

bool ends_with(std::string_view name, std::string_view ext) {
  if (name.size() <= ext.size()) return false;  // ".ply" alone is a name, not an extension
  const std::string_view tail = name.substr(name.size() - ext.size());
  return std::equal(tail.begin(), tail.end(), ext.begin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == b; });
}

template <class F>
const F* by_extension(std::span<const F* const> list, std::string_view name) {
  for (const F* f : list)
    for (std::string_view ext : f->extensions)
      if (ends_with(name, ext)) return f;
  return nullptr;
}

detected by_name(std::string_view name) {
  return {by_extension(scene_formats(), name), by_extension(particle_formats(), name)};
}

// The file's first bytes (a gzip file's, inflated), or "" where it cannot be
// read as a regular file.
std::string head_of(const std::string& path) {
  std::string head(4096, '\0');
  try {
    const std::unique_ptr<input::text_source> text = input::open_text(path);
    size_t got = 0;
    while (got < head.size())
      if (const size_t n = text->read(head.data() + got, head.size() - got)) got += n;
      else break;
    head.resize(got);
  } catch (const format_error&) {
    head.clear();
  }
  return head;
}

}  // namespace

std::span<const scene_format* const> scene_formats() { return scene_list; }
std::span<const format* const> particle_formats() { return particle_list(); }

detected detect(const std::string& path) {
  const std::string head = head_of(path);
  if (!head.empty()) {
    for (const format* f : particle_formats())
      if (f->sniff && f->sniff(head)) return {nullptr, f};
    for (const scene_format* f : scene_formats())
      if (f->sniff && f->sniff(head)) return {f, nullptr};
  }
  return by_name(path);
}

bool is_builtin_name(std::string_view name) { return builtin_spheres(name).has_value(); }

bool names_a_file(const std::string& name) {
  if (by_name(name)) return true;
  struct stat st {};
  return ::stat(name.c_str(), &st) == 0;
}

}  // namespace raycast::formats
