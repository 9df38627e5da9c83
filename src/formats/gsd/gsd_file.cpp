#include "formats/gsd/gsd_file.h"

#include <cstring>

#include "formats/format.h"
#include "formats/input/fields.h"

namespace raycast::formats::gsd {
namespace {

constexpr uint64_t magic = 0x65DF65DF65DF65DFull;
constexpr uint64_t header_bytes = 256, entry_bytes = 32, segment_bytes = 64;

[[noreturn]] void fail(const char* block, uint64_t byte, const std::string& what) {
  throw format_error(std::string(block) + " (byte " + std::to_string(byte) + "): " + what);
}

// Whether [offset, offset + count * each) lies within size, without overflow.
bool fits(uint64_t offset, uint64_t count, uint64_t each, uint64_t size) {
  return offset <= size && (each == 0 || count <= (size - offset) / each);
}

}  // namespace

size_t type_size(uint8_t type) {
  switch (type) {
    case u8: case i8: case character: return 1;
    case u16: case i16: return 2;
    case u32: case i32: case f32: return 4;
    case u64: case i64: case f64: return 8;
    default: return 0;
  }
}

bool has_gsd_magic(std::string_view head) {
  return head.size() >= 8 && load_le<uint64_t>(reinterpret_cast<const unsigned char*>(head.data())) == magic;
}

gsd_file::gsd_file(const unsigned char* data, uint64_t size, std::shared_ptr<const void> owner)
    : data_(data), size_(size), owner_(std::move(owner)) {
  if (size_ < header_bytes) fail("header", size_, "the file is shorter than GSD's 256-byte header");
  if (load_le<uint64_t>(data_) != magic) fail("header", 0, "not a GSD file (no magic number)");
  const uint32_t version = load_le<uint32_t>(data_ + 44);
  if ((version < (1u << 16) && version != 3) || version >= (3u << 16))
    fail("header", 44, "GSD file layer version " + std::to_string(version >> 16) + "." +
                           std::to_string(version & 0xffff) + " is not one this reader knows (1.0 to 2.x)");
  const char* schema = reinterpret_cast<const char*>(data_ + 112);
  schema_.assign(schema, strnlen(schema, 64));
  read_names(load_le<uint64_t>(data_ + 24), load_le<uint64_t>(data_ + 32), version < (2u << 16));
  read_index(load_le<uint64_t>(data_ + 8), load_le<uint64_t>(data_ + 16));
}

void gsd_file::read_names(uint64_t location, uint64_t segments, bool v1) {
  if (!fits(location, segments, segment_bytes, size_))
    fail("header", 24, "the name list (" + std::to_string(segments) + " segments at byte " + std::to_string(location) +
                           ") lies past the file's end");
  const char* p = reinterpret_cast<const char*>(data_ + location);
  const size_t n = size_t(segments * segment_bytes);
  for (size_t at = 0; at < n && p[at] != 0;) {
    const size_t room = v1 ? segment_bytes : n - at;
    const size_t len = strnlen(p + at, room);
    if (!v1 && len == room) fail("name list", location + at, "a name runs past the list's end");
    if (names_.size() == 65535) fail("name list", location + at, "more than 65535 names");
    names_.emplace_back(p + at, len);
    at += v1 ? segment_bytes : len + 1;
  }
}

chunk gsd_file::entry(size_t e) const {
  const unsigned char* p = index_ + e * entry_bytes;
  chunk c;
  c.frame = load_le<uint64_t>(p);
  c.N = load_le<uint64_t>(p + 8);
  c.location = load_le<uint64_t>(p + 16);
  c.M = load_le<uint32_t>(p + 24);
  c.id = load_le<uint16_t>(p + 28);
  c.type = p[30];
  c.entry = index_at_ + e * entry_bytes;
  return c;
}

void gsd_file::read_index(uint64_t location, uint64_t entries) {
  if (!fits(location, entries, entry_bytes, size_))
    fail("header", 8, "the index (" + std::to_string(entries) + " entries at byte " + std::to_string(location) +
                          ") lies past the file's end");
  index_ = data_ + location;
  index_at_ = location;
  uint64_t last = 0;
  for (entries_ = 0; entries_ < entries; ++entries_) {
    const chunk c = entry(size_t(entries_));
    if (c.location == 0) break;
    const size_t each = type_size(c.type);
    if (each == 0) fail("index", c.entry, "type " + std::to_string(c.type) + " is not a GSD type");
    if (c.id >= names_.size()) fail("index", c.entry, "name id " + std::to_string(c.id) + " is not in the name list");
    if (c.M == 0) fail("index", c.entry, "a chunk of no columns");
    if (c.frame < last) fail("index", c.entry, "frames out of order");
    if (c.frame >= entries) fail("index", c.entry, "frame " + std::to_string(c.frame) + " past the index's size");
    if (!fits(c.location, c.N, uint64_t(c.M) * each, size_) || uint64_t(c.M) * each > size_)
      fail("index", c.entry, input::printable(names_[c.id]) + " (" + std::to_string(c.N) + " x " + std::to_string(c.M) +
                                 " at byte " + std::to_string(c.location) + ") lies past the file's end");
    last = c.frame;
  }
  frames_ = entries_ == 0 ? 0 : size_t(last) + 1;
}

std::optional<chunk> gsd_file::find(size_t k, std::string_view name) const {
  size_t id = 0;
  while (id < names_.size() && names_[id] != name) ++id;
  if (id == names_.size()) return std::nullopt;
  // The first entry of frame k, by bisection (entries are sorted by frame).
  size_t lo = 0, hi = size_t(entries_);
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (load_le<uint64_t>(index_ + mid * entry_bytes) < k) lo = mid + 1;
    else hi = mid;
  }
  for (size_t e = lo; e < entries_ && load_le<uint64_t>(index_ + e * entry_bytes) == k; ++e)
    if (load_le<uint16_t>(index_ + e * entry_bytes + 28) == id) return entry(e);
  return std::nullopt;
}

std::vector<std::string_view> gsd_file::names(std::string_view prefix) const {
  std::vector<std::string_view> out;
  for (std::string_view n : names_)
    if (n.starts_with(prefix)) out.push_back(n);
  return out;
}

}  // namespace raycast::formats::gsd
