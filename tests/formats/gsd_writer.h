// A small GSD writer (file layer 2.0 or 1.0, as src/formats/gsd/gsd_file.h lays it
// out): the GSD tests' hand-made and hostile files, the fuzzer's seeds and
// the bench's 10^6-particle frame. The tests against the gsd package's own
// writer are test_formats_tools.cpp's.
#pragma once
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace raycast_test {

struct gsd_out {
  uint64_t frame = 0;
  std::string name;
  uint8_t type = 9;  // GSD's type ids: 3 uint32, 5 int8, 9 float32, 10 float64, 4 uint64
  uint64_t N = 0;
  uint32_t M = 1;
  std::string bytes;  // N x M values
};

template <class T>
std::string gsd_bytes(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

inline void put_le(std::string& s, size_t at, uint64_t v, int n) {
  for (int b = 0; b < n; ++b) s[at + size_t(b)] = char((v >> (8 * b)) & 0xff);
}

// The file of these chunks (in frame order), with the schema and the file
// layer version given (2.0 unless told).
inline std::string write_gsd(const std::vector<gsd_out>& chunks, const std::string& schema = "hoomd",
                             uint32_t version = 2u << 16) {
  std::string file(256, '\0');
  std::vector<std::string> names;
  std::vector<uint64_t> at;
  for (const gsd_out& c : chunks) {
    at.push_back(file.size());
    file += c.bytes;
    bool known = false;
    for (const std::string& n : names) known = known || n == c.name;
    if (!known) names.push_back(c.name);
  }
  const uint64_t names_at = file.size();
  std::string list;  // 2.x: 0-separated names; 1.0: one a 64-byte segment
  for (const std::string& n : names) list += version < (2u << 16) ? n + std::string(64 - n.size(), '\0') : n + '\0';
  list.resize((list.size() / 64 + 1) * 64, '\0');
  file += list;
  const uint64_t index_at = file.size();
  const uint64_t entries = chunks.size() + 4;  // room to spare, as gsd allocates
  std::string index(entries * 32, '\0');
  for (size_t k = 0; k < chunks.size(); ++k) {
    const gsd_out& c = chunks[k];
    uint64_t id = 0;
    while (names[id] != c.name) ++id;
    put_le(index, k * 32, c.frame, 8);
    put_le(index, k * 32 + 8, c.N, 8);
    put_le(index, k * 32 + 16, at[k], 8);
    put_le(index, k * 32 + 24, c.M, 4);
    put_le(index, k * 32 + 28, id, 2);
    index[k * 32 + 30] = char(c.type);
  }
  file += index;
  put_le(file, 0, 0x65DF65DF65DF65DFull, 8);
  put_le(file, 8, index_at, 8);
  put_le(file, 16, entries, 8);
  put_le(file, 24, names_at, 8);
  put_le(file, 32, list.size() / 64, 8);
  put_le(file, 40, 1u << 16, 4);
  put_le(file, 44, version, 4);
  std::memcpy(file.data() + 48, "raycast tests", 13);
  std::memcpy(file.data() + 112, schema.data(), std::min<size_t>(schema.size(), 63));
  return file;
}

// A HOOMD frame: N particles, their positions (x y z each), type ids and
// names, diameters (empty: none written), the box.
inline std::vector<gsd_out> hoomd_frame(uint64_t frame, const std::vector<float>& xyz, const std::vector<uint32_t>& typeid_,
                                        const std::vector<std::string>& types, const std::vector<float>& diameter,
                                        const std::vector<float>& box) {
  std::vector<gsd_out> out;
  const uint64_t n = xyz.size() / 3;
  out.push_back({frame, "configuration/box", 9, 6, 1, gsd_bytes(box)});
  out.push_back({frame, "particles/N", 3, 1, 1, gsd_bytes(std::vector<uint32_t>{uint32_t(n)})});
  out.push_back({frame, "particles/position", 9, n, 3, gsd_bytes(xyz)});
  if (!types.empty()) {
    uint32_t width = 0;
    for (const std::string& t : types) width = std::max(width, uint32_t(t.size() + 1));
    std::string b;
    for (const std::string& t : types) b += t + std::string(width - t.size(), '\0');
    out.push_back({frame, "particles/types", 5, types.size(), width, b});
  }
  if (!typeid_.empty()) out.push_back({frame, "particles/typeid", 3, n, 1, gsd_bytes(typeid_)});
  if (!diameter.empty()) out.push_back({frame, "particles/diameter", 9, n, 1, gsd_bytes(diameter)});
  return out;
}

}  // namespace raycast_test
