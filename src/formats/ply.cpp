#include "formats/ply.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <unordered_set>
#include <vector>

#include "memory/arrays.h"
#include "text/names.h"
#include "formats/ply/header.h"
#include "formats/regular_file.h"
#include "particles/spheres.h"

namespace raycast {
namespace {

using namespace ply_detail;

// The vertex element's roles: positions, radius and colour where given; every
// other property is the frame's by its name.
struct layout {
  const element* vertex = nullptr;
  const property* xyz[3] = {};
  const property* radius = nullptr;
  const property* rgb[3] = {};
  std::vector<const property*> others;
};

const property* one_of_types(const element& v, std::string_view name, bool reals_only, bool u8_too) {
  const property* p = v.find(name);
  if (!p) return nullptr;
  const std::string path = "vertex." + p->name;
  if (p->list) fail(path, "a list property; a vertex's properties must be single numbers", p->at);
  if (reals_only && !is_real(p->type) && !(u8_too && p->type == ply_type::u8))
    fail(path, std::string("is ") + std::string(types[size_t(p->type)].name) + "; want float or double" +
                   (u8_too ? " (0-1) or uchar (0-255)" : ""),
         p->at);
  return p;
}

// Three properties of one type (x y z, red green blue), all or none.
void triple_of(const element& v, const char* const names[3], bool u8_too, const property* out[3]) {
  int found = 0;
  for (int c = 0; c < 3; ++c) found += (out[c] = one_of_types(v, names[c], true, u8_too)) != nullptr;
  if (found == 0) return;
  for (int c = 0; c < 3; ++c)
    if (!out[c]) fail("vertex." + std::string(names[c]), "is missing (give all three of " + std::string(names[0]) + " " +
                                                             names[1] + " " + names[2] + ")", v.at);
  if (out[1]->type != out[0]->type || out[2]->type != out[0]->type)
    fail("vertex." + std::string(names[0]), "the three must have one type", out[0]->at);
}

layout layout_of(const header& h) {
  layout l;
  for (const element& e : h.elements)
    if (e.name == "vertex") l.vertex = &e;
  if (!l.vertex) fail("header", "has no vertex element (one sphere per vertex)", h.bytes);
  const element& v = *l.vertex;
  if (v.count == 0) fail("vertex", "has no vertices: nothing to render", v.at);
  if (v.count > max_spheres) fail("vertex", std::to_string(v.count) + " vertices; at most " + std::to_string(max_spheres) + " spheres", v.at);
  for (const property& p : v.props)
    if (p.list) fail("vertex." + p.name, "a list property; a vertex's properties must be single numbers", p.at);
  static const char* const xyz[3] = {"x", "y", "z"};
  static const char* const rgb[3] = {"red", "green", "blue"};
  triple_of(v, xyz, false, l.xyz);
  if (!l.xyz[0]) fail("vertex.x", "is missing: a vertex needs x, y and z (float or double)", v.at);
  l.radius = one_of_types(v, "radius", true, false);
  triple_of(v, rgb, true, l.rgb);
  for (const property& p : v.props)
    if (&p != l.xyz[0] && &p != l.xyz[1] && &p != l.xyz[2] && &p != l.radius && &p != l.rgb[0] && &p != l.rgb[1] &&
        &p != l.rgb[2])
      l.others.push_back(&p);
  return l;
}

// The byte after element e's rows in a binary body, from `at` (the element's
// first byte); rows with lists are walked, bounded by the body's end. base:
// the body's first byte in the file, for messages. (List counts are read as
// a little-endian machine does, then swapped where the file's order differs.)
uint64_t skip_binary(const element& e, const char* body, uint64_t size, uint64_t at, bool swap, uint64_t base) {
  if (!e.has_lists()) {
    if (e.row_bytes > 0 && e.count > (size - std::min(size, at)) / e.row_bytes)
      fail(e.name, "the header promises " + std::to_string(e.count) + " rows; the file ends first", base + size);
    return at + e.count * e.row_bytes;
  }
  for (uint64_t k = 0; k < e.count; ++k)
    for (const property& p : e.props) {
      uint64_t n = 1;
      if (p.list) {
        if (at + bytes_of(p.count_type) > size) fail(e.name, "the file ends inside row " + std::to_string(k), base + size);
        uint32_t c = 0;
        static_assert(std::endian::native == std::endian::little, "list counts are read as little-endian first");
        std::memcpy(&c, body + at, bytes_of(p.count_type));
        if (swap) c = __builtin_bswap32(c) >> (32 - 8 * bytes_of(p.count_type));
        at += bytes_of(p.count_type);
        n = c;
      }
      if (n * bytes_of(p.type) > size - std::min(size, at)) fail(e.name, "the file ends inside row " + std::to_string(k), base + size);
      at += n * bytes_of(p.type);
    }
  return at;
}

// A scalar of type t at p, in the file's byte order.
double value_at(const char* p, ply_type t, bool swap) {
  const auto load = [&]<class U>(U) {
    U b;
    std::memcpy(&b, p, sizeof b);
    if constexpr (sizeof(U) == 2) return swap ? __builtin_bswap16(b) : b;
    if constexpr (sizeof(U) == 4) return swap ? __builtin_bswap32(b) : b;
    if constexpr (sizeof(U) == 8) return swap ? __builtin_bswap64(b) : b;
  };
  switch (t) {
    case ply_type::i8: return double(int8_t(*p));
    case ply_type::u8: return double(uint8_t(*p));
    case ply_type::i16: return double(int16_t(load(uint16_t{})));
    case ply_type::u16: return double(load(uint16_t{}));
    case ply_type::i32: return double(int32_t(load(uint32_t{})));
    case ply_type::u32: return double(load(uint32_t{}));
    case ply_type::f32: return double(std::bit_cast<float>(load(uint32_t{})));
    case ply_type::f64: break;
  }
  return std::bit_cast<double>(load(uint64_t{}));
}

// What a sphere's values must be, each refusal naming the vertex, the property and the byte.
enum class role : uint8_t { coordinate, radius, color, other };
void check_value(role r, const property& p, uint64_t k, double v, uint64_t at) {
  const auto bad = [&](const std::string& why) { fail("vertex[" + std::to_string(k) + "]." + p.name, number_text(v) + why, at); };
  switch (r) {
    case role::coordinate:
      if (!std::isfinite(v)) bad(" is not a finite number");
      break;
    case role::radius:
      if (!std::isfinite(v)) bad(" is not a finite radius");
      if (!(v > 0.0)) bad(" is too small for a radius (it must be above 0)");
      if (v > max_sphere_extent) bad(" is too large for a radius (at most 1e37, the float renderers' range)");
      break;
    case role::color:
      if (!(std::abs(v) <= max_color)) bad(" is not a colour component (finite, within +-1e30)");
      break;
    case role::other: break;
  }
}

// Under AddressSanitizer the body is allocated to its exact size, so that a
// read past it is caught (huge pages round it up to 2 MiB of zeros).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool exact_body = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool exact_body = true;
#else
constexpr bool exact_body = false;
#endif
#else
constexpr bool exact_body = false;
#endif

// The memory a scene's spheres are read from, owned by its sphere arrays.
struct ply_storage {
  char* body = nullptr;  // the file's bytes after the header
  size_t body_bytes = 0;
  size_t mapped = 0;  // what map_huge was asked for (at least a byte)
  // Read out of order by the preparation, as the body is: in huge pages always.
  out_of_order_array<double> table;  // decoded rows (ASCII, uneven binary): x y z [radius] [r g b] [others]
  ply_storage() = default;
  ply_storage(const ply_storage&) = delete;
  ply_storage& operator=(const ply_storage&) = delete;
  ~ply_storage() {
    if (!body) return;
    if (exact_body) std::free(body);
    else unmap_huge(body, mapped);
  }
};

// The decoded table's columns: x y z, then the radius and r g b where read,
// then the other properties in the header's order.
struct table_columns {
  size_t width = 3, radius = 0, rgb = 0, others = 0;  // 0: not in the table
};
table_columns columns_of(const layout& l) {
  table_columns c;
  if (l.radius) c.radius = c.width++;
  if (l.rgb[0]) c.rgb = c.width, c.width += 3;
  c.others = c.width;
  c.width += l.others.size();
  return c;
}

using api::column;
// first's values in place, and the next components' at second's distance
// from them; nullopt for a type a column cannot read in place (16-bit and
// signed 8-bit integers), which the table holds decoded.
std::optional<column> file_column(const char* rows, const element& v, const property* first, const property* second,
                                  bool swap, bool colour = false) {
  const ptrdiff_t component = second ? ptrdiff_t(second->offset) - ptrdiff_t(first->offset) : 0;
  api::element type{};
  switch (first->type) {
    case ply_type::f32: type = api::element::f32; break;
    case ply_type::f64: type = api::element::f64; break;
    case ply_type::u8:
      if (!colour) return std::nullopt;  // a column's u8 is a colour, read as value / 255
      type = api::element::u8;
      break;
    case ply_type::u32: type = api::element::u32; break;
    case ply_type::i32: type = api::element::i32; break;
    default: return std::nullopt;
  }
  return column{rows + first->offset, type, ptrdiff_t(v.row_bytes), component, swap};
}

// Whether three properties lie at even steps (x y z in a row), so one column reads them.
bool evenly_spaced(const property* const p[3]) {
  return !p[0] || p[1]->offset - p[0]->offset == p[2]->offset - p[1]->offset;
}

// A binary vertex element's checks.
void check_binary(const layout& l, const char* rows, uint64_t file_at, bool swap) {
  const element& v = *l.vertex;
  for (uint64_t k = 0; k < v.count; ++k) {
    const char* row = rows + k * v.row_bytes;
    const uint64_t at = file_at + k * v.row_bytes;
    for (int c = 0; c < 3; ++c) {
      const property& p = *l.xyz[c];
      check_value(role::coordinate, p, k, value_at(row + p.offset, p.type, swap), at + p.offset);
      if (l.rgb[c] && is_real(l.rgb[c]->type))
        check_value(role::color, *l.rgb[c], k, value_at(row + l.rgb[c]->offset, l.rgb[c]->type, swap), at + l.rgb[c]->offset);
    }
    if (l.radius) check_value(role::radius, *l.radius, k, value_at(row + l.radius->offset, l.radius->type, swap), at + l.radius->offset);
  }
}

// The properties a binary body's columns cannot read in place, decoded into
// the table: all of them where x y z or r g b are not evenly spaced (`all`),
// else the others of the types a column has not.
void decode_binary(const layout& l, const char* rows, bool swap, bool all, ply_storage& st) {
  const table_columns tc = columns_of(l);
  const element& v = *l.vertex;
  st.table.resize(v.count * tc.width);
  const auto decoded = [&](const property* p) { return all || !file_column(rows, v, p, nullptr, swap); };
  for (uint64_t k = 0; k < v.count; ++k) {
    const char* row = rows + k * v.row_bytes;
    double* out = st.table.data() + k * tc.width;
    for (int c = 0; c < 3 && all; ++c) {
      out[c] = value_at(row + l.xyz[c]->offset, l.xyz[c]->type, swap);
      if (tc.rgb) {
        const double x = value_at(row + l.rgb[c]->offset, l.rgb[c]->type, swap);
        out[tc.rgb + size_t(c)] = l.rgb[c]->type == ply_type::u8 ? x / 255.0 : x;
      }
    }
    if (tc.radius && all) out[tc.radius] = value_at(row + l.radius->offset, l.radius->type, swap);
    for (size_t i = 0; i < l.others.size(); ++i)
      if (decoded(l.others[i])) out[tc.others + i] = value_at(row + l.others[i]->offset, l.others[i]->type, swap);
  }
}

// Table column c (doubles, tc.width a row), components of it a row.
column table_column(const ply_storage& st, const table_columns& tc, size_t c) {
  const ptrdiff_t row = ptrdiff_t(tc.width * sizeof(double));
  return column{st.table.data() + c, api::element::f64, row, sizeof(double), false};
}

// The frame's columns from the table (ASCII, uneven binary).
void frame_of_table(const layout& l, const ply_storage& st, particle_frame& f) {
  const table_columns tc = columns_of(l);
  f.positions = table_column(st, tc, 0);
  if (tc.radius) f.radii = table_column(st, tc, tc.radius);
  if (tc.rgb) f.colors = table_column(st, tc, tc.rgb);
  for (size_t i = 0; i < l.others.size(); ++i) f.properties.push_back({l.others[i]->name, table_column(st, tc, tc.others + i)});
}

// The vertex element's rows in a binary body: read in place, or decoded.
void read_binary(const header& h, const layout& l, ply_storage& st, particle_frame& f) {
  const bool swap = (h.format == encoding::big) != (std::endian::native == std::endian::big);
  uint64_t at = 0;
  for (const element& e : h.elements) {
    if (&e == l.vertex) break;
    at = skip_binary(e, st.body, st.body_bytes, at, swap, h.bytes);
  }
  const element& v = *l.vertex;
  const uint64_t room = st.body_bytes - std::min<uint64_t>(st.body_bytes, at);
  if (v.count > room / v.row_bytes)
    fail("vertex", "the header promises " + std::to_string(v.count) + " vertices of " + std::to_string(v.row_bytes) +
                       " bytes from byte " + std::to_string(h.bytes + at) + ", but the file ends after " +
                       std::to_string(room / v.row_bytes) + " of them",
         h.bytes + st.body_bytes);
  const char* rows = st.body + at;
  check_binary(l, rows, h.bytes + at, swap);
  const bool all = !evenly_spaced(l.xyz) || !evenly_spaced(l.rgb);
  const bool any = std::any_of(l.others.begin(), l.others.end(), [&](const property* p) { return !file_column(rows, v, p, nullptr, swap); });
  if (all || any) decode_binary(l, rows, swap, all, st);
  if (all) return frame_of_table(l, st, f);
  const table_columns tc = columns_of(l);
  f.positions = *file_column(rows, v, l.xyz[0], l.xyz[1], swap);
  if (l.radius) f.radii = *file_column(rows, v, l.radius, nullptr, swap);
  if (l.rgb[0]) f.colors = *file_column(rows, v, l.rgb[0], l.rgb[1], swap, true);
  for (size_t i = 0; i < l.others.size(); ++i) {
    const std::optional<column> c = file_column(rows, v, l.others[i], nullptr, swap);
    f.properties.push_back({l.others[i]->name, c ? *c : table_column(st, tc, tc.others + i)});
  }
}

// An ASCII body's words, with their byte offsets in the file.
struct words {
  const char* p;
  const char* end;
  const char* begin;
  uint64_t base;  // the body's first byte in the file
  static bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  std::string_view next() {
    while (p < end && space(*p)) ++p;
    const char* start = p;
    while (p < end && !space(*p)) ++p;
    return {start, size_t(p - start)};
  }
  uint64_t offset(std::string_view w) const { return base + uint64_t(w.data() - begin); }
};

// An ASCII number of type t, rounded to it (a float property is a float).
double ascii_number(std::string_view w, ply_type t, const std::string& path, uint64_t at) {
  const char* end = w.data() + w.size();
  if (is_real(t)) {
    double d = 0.0;
    float f = 0.0f;
    const auto r = t == ply_type::f32 ? std::from_chars(w.data(), end, f) : std::from_chars(w.data(), end, d);
    if (r.ec == std::errc() && r.ptr == end) return t == ply_type::f32 ? double(f) : d;
    if (r.ec == std::errc::result_out_of_range)
      fail(path, quote_token(w) + (std::isinf(std::strtod(std::string(w).c_str(), nullptr))
                                       ? (w.starts_with('-') ? " is too far below zero" : " is too large")
                                       : " is too near 0") + " for a " +
                     std::string(types[size_t(t)].name),
           at);
    fail(path, quote_token(w) + " is not a number", at);
  }
  int64_t i = 0;
  const auto r = std::from_chars(w.data(), end, i);
  const int bits = 8 * int(bytes_of(t));
  const bool is_signed = t == ply_type::i8 || t == ply_type::i16 || t == ply_type::i32;
  const int64_t lo = is_signed ? -(int64_t(1) << (bits - 1)) : 0;
  const int64_t hi = is_signed ? (int64_t(1) << (bits - 1)) - 1 : (int64_t(1) << bits) - 1;
  if (r.ec != std::errc() || r.ptr != end || i < lo || i > hi)
    fail(path, quote_token(w) + " is not a " + std::string(types[size_t(t)].name) + " (a whole number from " +
                   std::to_string(lo) + " to " + std::to_string(hi) + ")",
         at);
  return double(i);
}

// Where each vertex property of an ASCII row goes: its table column and
// what its value must be.
struct slot {
  size_t column = 0;
  role what = role::other;
  bool byte_color = false;  // uchar red green blue: value / 255
};
std::vector<slot> slots_of(const layout& l) {
  const table_columns tc = columns_of(l);
  std::vector<slot> s(l.vertex->props.size());
  const auto index = [&](const property* p) { return size_t(p - l.vertex->props.data()); };
  for (int c = 0; c < 3; ++c) {
    s[index(l.xyz[c])] = {size_t(c), role::coordinate};
    if (l.rgb[0]) s[index(l.rgb[c])] = {tc.rgb + size_t(c), role::color, l.rgb[c]->type == ply_type::u8};
  }
  if (l.radius) s[index(l.radius)] = {tc.radius, role::radius};
  for (size_t i = 0; i < l.others.size(); ++i) s[index(l.others[i])] = {tc.others + i, role::other};
  return s;
}

// Skips an ASCII element's rows.
void skip_ascii(const element& e, words& w) {
  if (e.props.empty()) return;
  for (uint64_t k = 0; k < e.count; ++k)
    for (const property& p : e.props) {
      const std::string_view first = w.next();
      if (first.empty()) fail(e.name, "the file ends after " + std::to_string(k) + " of " + std::to_string(e.count) + " rows", w.offset(first));
      if (!p.list) continue;
      const double n = ascii_number(first, p.count_type, e.name + "." + p.name, w.offset(first));
      for (double i = 0; i < n; ++i)
        if (w.next().empty()) fail(e.name, "the file ends inside row " + std::to_string(k), w.offset({w.p, 0}));
    }
}

void read_ascii(const header& h, const layout& l, ply_storage& st, particle_frame& f) {
  words w{st.body, st.body + st.body_bytes, st.body, h.bytes};
  for (const element& e : h.elements) {
    if (&e == l.vertex) break;
    skip_ascii(e, w);
  }
  const element& v = *l.vertex;
  const uint64_t left = uint64_t(w.end - w.p), numbers = v.props.size();
  // Each number takes at least two bytes but the last: more promised cannot be there.
  if (v.count > (left + 1) / 2 / numbers)
    fail("vertex", "the header promises " + std::to_string(v.count) + " vertices of " + std::to_string(numbers) +
                       " numbers; the " + std::to_string(left) + " bytes left hold at most " +
                       std::to_string((left + 1) / 2 / numbers),
         h.bytes + st.body_bytes);
  const std::vector<slot> slots = slots_of(l);
  const size_t width = columns_of(l).width;
  st.table.resize(v.count * width);
  for (uint64_t k = 0; k < v.count; ++k) {
    double* row = st.table.data() + k * width;
    for (size_t i = 0; i < slots.size(); ++i) {
      const std::string_view t = w.next();
      const property& p = v.props[i];
      if (t.empty()) fail("vertex", "the file ends after " + std::to_string(k) + " of " + std::to_string(v.count) + " vertices", w.offset(t));
      const slot& s = slots[i];
      const double x = ascii_number(t, p.type, "vertex[" + std::to_string(k) + "]." + p.name, w.offset(t));
      check_value(s.what, p, k, x, w.offset(t));
      row[s.column] = s.byte_color ? x / 255.0 : x;
    }
  }
  frame_of_table(l, st, f);
}

// The body after the header, read once; a file that changes meanwhile is refused.
std::shared_ptr<ply_storage> read_body(const byte_source& src, const header& h) {
  auto st = std::make_shared<ply_storage>();
  st->body_bytes = size_t(src.size - h.bytes);
  st->mapped = std::max<size_t>(st->body_bytes, 1);
  // Huge pages always: the preparation reads it out of order (a TLB miss a
  // sphere costs more than the faults: 10^8 spheres 22 s, not 28 s).
  st->body = static_cast<char*>(exact_body ? std::malloc(st->mapped) : map_huge(st->mapped, true));
  if (!st->body) throw formats::format_error("out of memory reading " + std::to_string(st->body_bytes) + " bytes", true);
  const ptrdiff_t got = src.read(h.bytes, st->body_bytes, st->body);
  if (got < 0) throw formats::format_error(std::strerror(errno), true);
  if (size_t(got) != st->body_bytes || !src.unchanged())
    throw formats::format_error("changed while being read (it was " + std::to_string(src.size) + " bytes)");
  return st;
}

}  // namespace

byte_source memory_source(std::string_view bytes) {
  byte_source src;
  src.size = bytes.size();
  src.read = [bytes](uint64_t offset, size_t n, char* to) {
    const size_t got = offset >= bytes.size() ? 0 : std::min(n, bytes.size() - size_t(offset));
    std::memcpy(to, bytes.data() + offset, got);
    return ptrdiff_t(got);
  };
  src.unchanged = [] { return true; };
  return src;
}

particle_frame read_ply_frame(const byte_source& src) try {
  std::string head(size_t(std::min<uint64_t>(src.size, max_ply_header_bytes)), '\0');
  const ptrdiff_t got = src.read(0, head.size(), head.data());
  if (got < 0) throw formats::format_error(std::strerror(errno), true);
  head.resize(size_t(got));
  const header h = parse_header(head, src.size);
  const layout l = layout_of(h);
  const std::shared_ptr<ply_storage> st = read_body(src, h);
  particle_frame f;
  f.count = size_t(l.vertex->count);
  if (h.format == encoding::ascii) read_ascii(h, l, *st, f);
  else read_binary(h, l, *st, f);
  f.owner = st;
  return f;
} catch (const ply_error& e) {
  throw formats::format_error(e.path.empty() ? e.message : e.path + ": " + e.message);
}

std::variant<scene_file_contents, scene_file_error> read_ply(const byte_source& src, const api::particles& o) try {
  particle_spheres s = spheres_of(read_ply_frame(src), o);
  scene_file_contents c;
  c.scene.arrays = std::move(s.arrays);
  return c;
} catch (const formats::format_error& e) {
  const std::string_view m = e.what();
  const size_t colon = m.find(": ");
  const bool pathed = !e.io && colon != std::string_view::npos && m.substr(0, colon).find(' ') == std::string_view::npos;
  if (pathed) return scene_file_error{std::string(m.substr(0, colon)), std::string(m.substr(colon + 2))};
  return scene_file_error{"", std::string(m), e.io};
} catch (const particle_refusal& e) {
  return scene_file_error{e.keyword, e.what()};
}

namespace {

// A file's bytes as a source, while f lives.
byte_source file_source(const regular_file& f) {
  byte_source src;
  src.size = f.size();
  src.read = [&f](uint64_t offset, size_t n, char* to) { return f.read_at(offset, n, to); };
  src.unchanged = [&f] { return f.unchanged(); };
  return src;
}

std::unique_ptr<regular_file> opened(const std::string& path) {
  auto r = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&r)) throw formats::format_error(*why, true);
  return std::move(std::get<std::unique_ptr<regular_file>>(r));
}

// A PLY file is one frame.
class ply_trajectory : public formats::trajectory {
 public:
  explicit ply_trajectory(std::string path) : path_(std::move(path)) {}
  size_t frame_count() override { return 1; }
  particle_frame read(size_t, const formats::wanted_columns&) override {
    const std::unique_ptr<regular_file> f = opened(path_);
    return read_ply_frame(file_source(*f));
  }

 private:
  std::string path_;
};

constexpr std::string_view ply_extensions[] = {".ply"};
bool ply_sniff(std::string_view head) { return head.starts_with("ply\n") || head.starts_with("ply\r\n"); }

}  // namespace

std::variant<scene_file_contents, scene_file_error> read_ply_file(const std::string& path, const api::particles& o) {
  auto r = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&r)) return scene_file_error{"", *why, true};
  return read_ply(file_source(*std::get<std::unique_ptr<regular_file>>(r)), o);
}

const formats::format& ply_format() {
  static const formats::format f{"ply", ply_extensions, ply_sniff, [](const std::string& path) {
                                   opened(path);  // a file that cannot be read is refused on opening
                                   return std::unique_ptr<formats::trajectory>(new ply_trajectory(path));
                                 }};
  return f;
}

}  // namespace raycast
