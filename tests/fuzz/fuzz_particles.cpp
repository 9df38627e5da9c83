// libFuzzer target: the particle readers (LAMMPS dumps, XYZ, GSD; plain or
// gzipped texts), from the first byte to every frame's every value.
//
// The first byte chooses: bits 0-1 the reader (0 LAMMPS dump, 1 XYZ, 2 GSD,
// 3 by content as the registry sniffs: GSD's magic, a dump's ITEM:, else
// XYZ); bit 2 every column wanted or none. The rest is the file. Checked:
//   - a refusal is one format_error line, never an I/O one (the bytes are in
//     memory), naming where: "frame K (line L): ..." for a text (L within
//     the text's lines but one, where it is not gzipped), "frame K (byte B)",
//     "header (byte B)", "index (byte B)" or "name list (byte B)" for GSD
//     (B within the file);
//   - an accepted frame's positions and radii are finite, its types index
//     its type names, and every property value can be read; frames read
//     again, last first, give the same positions.
// AddressSanitizer and UndefinedBehaviorSanitizer catch the rest: a view past
// a chunk, a count that overflows, an allocation a header's count asks for
// (-rss_limit_mb, -malloc_limit_mb).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "formats/gsd/gsd_file.h"
#include "formats/gsd/hoomd.h"
#include "formats/lammps/dump_header.h"
#include "formats/lammps/lammps_dump.h"
#include "formats/xyz/extxyz.h"

namespace {

using namespace raycast;
using namespace raycast::formats;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_particles: %s\n", what.c_str());
  std::abort();
}

// The number after `key` in a message, or -1.
long long after(const std::string& m, const char* key) {
  const size_t at = m.find(key);
  return at == std::string::npos ? -1 : std::strtoll(m.c_str() + at + std::string(key).size(), nullptr, 10);
}

void check_refusal(const format_error& e, const std::string& bytes, bool text) {
  const std::string m = e.what();
  if (m.empty() || m.find('\n') != std::string::npos) fail("not one line: " + m);
  if (e.io) fail("an I/O error from memory: " + m);
  if (text) {
    if (!m.starts_with("frame ")) fail("names no frame: " + m);
    if (m.find(": the file has ") != std::string::npos) return;
    const long long line = after(m, "(line ");
    if (line < 1) fail("names no line: " + m);
    const bool gz = bytes.size() >= 2 && uint8_t(bytes[0]) == 0x1f && uint8_t(bytes[1]) == 0x8b;
    if (!gz && line > std::count(bytes.begin(), bytes.end(), '\n') + 2) fail("a line past the text's end: " + m);
    return;
  }
  if (m.find(": the file has ") != std::string::npos) return;
  const long long byte = after(m, "(byte ");
  const bool named = m.starts_with("frame ") || m.starts_with("header (") || m.starts_with("index (") ||
                     m.starts_with("name list (");
  if (!named || byte < 0) fail("names no block and byte: " + m);
  if (uint64_t(byte) > bytes.size()) fail("a byte past the file's end: " + m);
}

void check_frame(const particle_frame& f) {
  for (size_t k = 0; k < f.count; ++k) {
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(f.positions.get(k, c))) fail("a position that is not finite");
    if (f.radii && !std::isfinite(f.radii->get(k))) fail("a radius that is not finite");
    if (f.types && !(f.types->get(k) < double(f.type_names.size()))) fail("a type past the type names");
    for (const particle_property& p : f.properties)
      for (int c = 0; c < p.components; ++c) (void)p.values.get(k, c);
  }
}

std::unique_ptr<trajectory> open(int reader, const std::string& bytes, const std::shared_ptr<const std::string>& keep) {
  if (reader == 3) reader = gsd::has_gsd_magic(bytes) ? 2 : lammps::looks_like_dump(bytes) ? 0 : 1;
  if (reader == 2) return open_gsd(reinterpret_cast<const unsigned char*>(keep->data()), keep->size(), keep);
  auto text = input::memory_text(keep->data(), keep->size());
  return reader == 0 ? open_lammps_dump(std::move(text)) : open_xyz(std::move(text));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  auto keep = std::make_shared<const std::string>(reinterpret_cast<const char*>(data + 1), size - 1);
  const int reader = data[0] & 3;
  wanted_columns wanted;
  wanted.all = (data[0] & 4) != 0;
  const bool text = reader == 3 ? !gsd::has_gsd_magic(*keep) : reader != 2;
  try {
    auto t = open(reader, *keep, keep);
    const size_t n = std::min<size_t>(t->frame_count(), 64);
    std::vector<particle_frame> frames;
    for (size_t k = 0; k < n; ++k) {
      frames.push_back(t->read(k, wanted));
      check_frame(frames.back());
    }
    for (size_t k = n; k-- > 0;) {
      const particle_frame again = t->read(k, wanted);
      if (again.count != frames[k].count) fail("a frame read again has another count");
      for (size_t r = 0; r < again.count; ++r)
        for (int c = 0; c < 3; ++c)
          if (again.positions.get(r, c) != frames[k].positions.get(r, c)) fail("a frame read again moved");
    }
  } catch (const format_error& e) {
    check_refusal(e, *keep, text);
  }
  return 0;
}
