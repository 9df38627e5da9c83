// A PLY file's header (Greg Turk's format), parsed: its encoding, elements
// and their properties, where each is in the file, and the refusal type the
// whole reader throws (its path and message with the byte it names).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace raycast::ply_detail {

// PLY's scalar types, each under its two names.
enum class ply_type : uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };
struct type_info {
  std::string_view name, other_name;
  uint8_t bytes;
};
constexpr type_info types[] = {{"char", "int8", 1},    {"uchar", "uint8", 1},   {"short", "int16", 2},
                               {"ushort", "uint16", 2}, {"int", "int32", 4},     {"uint", "uint32", 4},
                               {"float", "float32", 4}, {"double", "float64", 8}};
constexpr std::string_view type_names[] = {"char",  "uchar", "short", "ushort", "int",    "uint",
                                           "float", "double", "int8",  "uint8",  "int16",  "uint16",
                                           "int32", "uint32", "float32", "float64"};
inline size_t bytes_of(ply_type t) { return types[size_t(t)].bytes; }
inline bool is_real(ply_type t) { return t == ply_type::f32 || t == ply_type::f64; }

enum class encoding : uint8_t { ascii, little, big };

struct property {
  std::string name;
  ply_type type = ply_type::f32;
  bool list = false;
  ply_type count_type = ply_type::u8;  // a list's
  size_t offset = 0;                   // in a binary row of scalars
  uint64_t at = 0;                     // the header line's byte
};

struct element {
  std::string name;
  uint64_t count = 0;
  std::vector<property> props;
  uint64_t at = 0;
  size_t row_bytes = 0;  // binary rows of scalars only
  bool has_lists() const {
    return std::any_of(props.begin(), props.end(), [](const property& p) { return p.list; });
  }
  std::unordered_set<std::string> names;  // the properties', for the duplicate check
  const property* find(std::string_view n) const {
    for (const property& p : props)
      if (p.name == n) return &p;
    return nullptr;
  }
};

struct header {
  encoding format = encoding::ascii;
  std::vector<element> elements;
  uint64_t bytes = 0;  // up to and including end_header's line
};

inline std::string at_byte(uint64_t offset) { return " (at byte " + std::to_string(offset) + ")"; }

// A refusal: which part of the file, why, where.
struct ply_error {
  std::string path, message;
};
// A file's names in a message, cut short: a header may hold a name of a megabyte.
std::string shown(std::string_view text, size_t most = 128);
[[noreturn]] void fail(std::string path, std::string why, uint64_t offset);

// The header from the file's first bytes (all of them, or max_ply_header_bytes).
header parse_header(std::string_view text, uint64_t file_size);

}  // namespace raycast::ply_detail
