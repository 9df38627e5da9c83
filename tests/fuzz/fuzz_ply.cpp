// libFuzzer target: particle files (formats/ply.h), from the header to pixels.
//
// The input is a PLY file's bytes, read from memory by read_ply with
// --radius or not and --color-by the third vertex property or not (two bits
// of the first byte choose; the rest is the file). Checked:
//   - a refusal is one line naming where: a path ("header", "vertex",
//     "vertex.NAME", "vertex[K].NAME" or "" for the whole file) and a
//     message ending in "(at byte N)" with N within the file; or, where
//     the file reads but the options cannot make spheres of it (no radius,
//     no such column), the setting it names;
//   - an accepted file has at least one sphere, and every sphere passes the
//     scene's own checks (validate());
//   - a small render of it (16 x 9, the scalar and best backends) gives the
//     same bytes in exact mode.
// AddressSanitizer and UndefinedBehaviorSanitizer catch the rest: reads past
// the body (allocated to its exact size in a sanitized build), counts that
// overflow, allocations a header's count asks for (-rss_limit_mb).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <variant>
#include <vector>

#include "render/backend.h"
#include "render/render.h"
#include "formats/ply.h"

namespace {

using namespace raycast;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_ply: %s\n", what.c_str());
  std::abort();
}

// Whether the file's bytes alone are read (the refusal is then the
// options' for this file: no radius given where the file has none, a
// --color-by column it lacks).
bool read_frame_alone(const byte_source& src) {
  try {
    (void)read_ply_frame(src);
    return true;
  } catch (const formats::format_error&) {
    return false;
  }
}

void check_refusal(const scene_file_error& e, size_t size, bool frame_was_read) {
  if (e.message.empty() || e.message.find('\n') != std::string::npos) fail("not one line: " + e.message);
  if (e.io) return;  // a read that failed: strerror's words
  if (frame_was_read) {  // names the setting, not a byte
    if (e.path.empty()) fail("an options' refusal naming no setting: " + e.message);
    return;
  }
  const size_t at = e.message.rfind("(at byte ");
  if (e.path.empty() && e.message.starts_with("changed while being read")) fail("a memory source cannot change");
  if (at == std::string::npos || e.message.back() != ')') fail("no byte offset: " + e.message);
  if (std::strtoull(e.message.c_str() + at + 9, nullptr, 10) > size) fail("a byte past the end: " + e.message);
}

std::vector<unsigned char> render_small(const scene& s, backend b) {
  render_options o;
  o.which = b;
  o.threads = 1;
  const renderer r(s, o);
  std::vector<unsigned char> out(16 * 9 * 3, 0xCD);
  r.render(image_band{out.data(), 16 * 3, pixel_format::rgb8, 0, 9});
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  api::particles o;
  if (data[0] & 1) o.radius = 0.25;
  if (data[0] & 2) o.color_by = "z";
  const byte_source src = memory_source(bytes);
  auto read = read_ply(src, o);
  if (auto* e = std::get_if<scene_file_error>(&read)) {
    check_refusal(*e, bytes.size(), read_frame_alone(src));
    return 0;
  }
  api::scene p = std::move(std::get<scene_file_contents>(read).scene);
  if (!p.arrays || p.arrays->count == 0) fail("accepted without spheres");
  for (size_t k = 0; k < p.arrays->count; ++k)
    if (auto e = validate(p.arrays->at(k), k)) fail("accepted an invalid sphere: " + path(*e) + ": " + e->message);
  p.cam.width = 16;
  p.cam.height = 9;
  p.cam.lookfrom = vec3(0.0, 0.0, 10.0);
  if (validate(p)) return 0;  // a centre too far from the camera for the float renderers: refused there
  const scene s = make_scene(p);
  const auto want = render_small(s, backend::scalar);
  if (render_small(s, backend::automatic) != want) fail("the best backend differs from the scalar one");
  return 0;
}
