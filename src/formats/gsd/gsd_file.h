// GSD's file layer (HOOMD-blue's General Simulation Data, versions 1.0 and
// 2.x), read in place from the file's bytes:
//
//   header (256 bytes, at 0)  magic 0x65DF65DF65DF65DF, index location and
//                             entries, name list location and 64-byte
//                             segments, schema and file versions,
//                             application and schema names
//   index (32 bytes an entry) frame, N, location, M, name id, type, flags;
//                             sorted by frame; the first of location 0 ends it
//   name list                 the chunk names (v2: 0-separated; v1: one a
//                             64-byte segment); the first empty one ends it
//   data chunks               N x M values of the entry's type at location
//
// Opening checks the header, the name list and every index entry against
// the file's size (types, dimensions, frames in order); a chunk is then a
// view of the file's bytes. Numbers are little-endian (GSD writes the
// machine's order, and every machine that writes it is little-endian).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace raycast::formats::gsd {

enum gsd_type : uint8_t { u8 = 1, u16, u32, u64, i8, i16, i32, i64, f32, f64, character };
size_t type_size(uint8_t type);  // 0 for a type GSD does not define

struct chunk {
  uint64_t frame = 0, N = 0, location = 0;
  uint32_t M = 0;
  uint16_t id = 0;
  uint8_t type = 0;
  uint64_t entry = 0;  // the index entry's byte offset, for messages
  uint64_t bytes() const { return N * M * type_size(type); }
};

class gsd_file {
 public:
  // The file's bytes (kept alive by owner). Throws format_error
  // "header (byte B): ..." or "index (byte B): ...".
  gsd_file(const unsigned char* data, uint64_t size, std::shared_ptr<const void> owner);

  size_t frames() const { return frames_; }
  std::string_view schema() const { return schema_; }
  // Frame k's chunk of this name, if it has one.
  std::optional<chunk> find(size_t k, std::string_view name) const;
  // The names of chunks that begin with prefix ("particles/").
  std::vector<std::string_view> names(std::string_view prefix) const;
  const unsigned char* at(uint64_t location) const { return data_ + location; }
  const std::shared_ptr<const void>& owner() const { return owner_; }

 private:
  void read_names(uint64_t location, uint64_t segments, bool v1);
  void read_index(uint64_t location, uint64_t entries);
  chunk entry(size_t e) const;  // index entry e, as the file has it

  const unsigned char* data_;
  uint64_t size_;
  std::shared_ptr<const void> owner_;
  std::string schema_;
  std::vector<std::string_view> names_;  // id -> name, views of the file's bytes
  const unsigned char* index_ = nullptr; // the index, read in place: entries_ used entries
  uint64_t index_at_ = 0, entries_ = 0;
  size_t frames_ = 0;
};

// Whether bytes begin with GSD's magic.
bool has_gsd_magic(std::string_view head);

// A little-endian number at p.
template <class U>
U load_le(const unsigned char* p) {
  U v = 0;
  for (size_t b = 0; b < sizeof(U); ++b) v = U(v | U(U(p[b]) << (8 * b)));
  return v;
}

}  // namespace raycast::formats::gsd
