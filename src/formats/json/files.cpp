// formats/json.h: a scene file's text or file, whole or a window at a time.
#include <cerrno>
#include <cstring>

#include "formats/json/reader.h"
#include "formats/regular_file.h"

namespace raycast {

using namespace json_detail;


std::optional<scene_file_contents> read_scene_windows(std::string_view text, size_t window) {
  const auto copy = [&](size_t offset, size_t n, char* to) {
    std::memcpy(to, text.data() + offset, n);
    return true;
  };
  return read_windowed(copy, text.size(), std::max<size_t>(window, 1));
}

std::variant<scene_file_contents, scene_file_error> read_scene_text(std::string_view text) {
  if (text.size() > max_scene_file_bytes) return too_large(text.size());
  if (text.size() >= windowed_from)
    if (auto c = read_scene_windows(text, default_window)) return std::move(*c);
  auto t = padded_text::allocate(text.size());
  if (!t) return scene_file_error{"", "out of memory copying " + bytes_text(text.size())};
  std::memcpy(t->data(), text.data(), text.size());
  t->finish(text.size());
  return parse_padded(*t);
}

std::variant<scene_file_contents, scene_file_error> read_scene_file(const std::string& path) {
  const auto error = [](std::string why) { return scene_file_error{"", std::move(why), true}; };
  auto opened = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&opened)) return error(*why);
  regular_file& f = *std::get<std::unique_ptr<regular_file>>(opened);
  if (f.size() > max_scene_file_bytes) return too_large(f.size());
  const size_t size = size_t(f.size());
  if (size >= windowed_from) {
    // Read at offsets, a window at a time; a file that changes length meanwhile
    // is left to the whole read below, which reports it.
    const auto at = [&](size_t offset, size_t n, char* to) { return f.read_at(offset, n, to) == ptrdiff_t(n); };
    if (auto c = read_windowed(at, size, default_window))
      if (f.unchanged()) return std::move(*c);
  }
  // Room for the size fstat gave and one byte more: a file that grows while
  // read is refused at that byte, so memory never exceeds what was checked.
  auto t = padded_text::allocate(size);
  if (!t) return error("out of memory reading " + bytes_text(size));
  const ptrdiff_t got = f.read_at(0, size + 1, t->data());
  if (got < 0) return error(std::strerror(errno));
  if (size_t(got) > size) return error("grew while being read (was " + bytes_text(size) + ")");
  f.close();
  t->finish(size_t(got));
  return parse_padded(*t);
}

namespace {

// The file's camera and sky keys applied to the lesson's, as nothing overrides them.
std::variant<api::scene, scene_file_error> resolved(std::variant<scene_file_contents, scene_file_error>&& r) {
  if (auto* e = std::get_if<scene_file_error>(&r)) return std::move(*e);
  scene_file_contents& c = std::get<scene_file_contents>(r);
  if (auto e = resolve_scene(c.keys, c.scene)) return scene_file_error{e->source, e->message};
  return std::move(c.scene);
}

}  // namespace

std::variant<api::scene, scene_file_error> parse_scene_file(std::string_view text) {
  return resolved(read_scene_text(text));
}

std::variant<api::scene, scene_file_error> load_scene_file(const std::string& path) {
  return resolved(read_scene_file(path));
}

}  // namespace raycast
