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
#include "particles/colormap.h"

namespace raycast {
namespace {

using namespace ply_detail;

// The spheres' properties in the vertex element.
struct layout {
  const element* vertex = nullptr;
  uint64_t vertex_at = 0;  // its first row's byte (binary)
  const property* xyz[3] = {};
  const property* radius = nullptr;
  const property* rgb[3] = {};
  const property* color_by = nullptr;
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

layout layout_of(const header& h, const api::particles& o) {
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
  if (!o.radius) {
    l.radius = one_of_types(v, "radius", true, false);
    if (!l.radius) fail("vertex.radius", "is missing: give every sphere one with --radius R", v.at);
  }
  triple_of(v, rgb, true, l.rgb);
  if (!o.color_by.empty()) {
    l.color_by = v.find(o.color_by);
    if (!l.color_by) {
      std::vector<std::string_view> names;
      for (const property& p : v.props) names.push_back(p.name);
      fail("vertex." + o.color_by, "no such property (it has: " + [&] {
        std::string s;
        for (std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
        return s;
      }() + ")" + did_you_mean(o.color_by, names), v.at);
    }
  }
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

std::string number_text(double x) {
  char buf[32];
  const auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, p) : "?";
}

// What a sphere's values must be, each refusal naming the vertex, the property and the byte.
enum class role : uint8_t { coordinate, radius, color, shown, other };
void check_value(role r, const property& p, uint64_t k, double v, uint64_t at) {
  const auto bad = [&](const std::string& why) { fail("vertex[" + std::to_string(k) + "]." + p.name, number_text(v) + why, at); };
  switch (r) {
    case role::coordinate:
    case role::shown:
      if (!std::isfinite(v)) bad(r == role::shown ? " cannot be coloured: not a finite number" : " is not a finite number");
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
  out_of_order_array<double> table;  // decoded rows (ASCII, uneven binary): x y z [radius] [r g b]
  out_of_order_array<float> colors;  // --color-by's, 3 a sphere
  double radius = 0.0;               // --radius's
  ply_storage() = default;
  ply_storage(const ply_storage&) = delete;
  ply_storage& operator=(const ply_storage&) = delete;
  ~ply_storage() {
    if (!body) return;
    if (exact_body) std::free(body);
    else unmap_huge(body, mapped);
  }
};

// The decoded table's columns: x y z, then the radius and r g b where read.
struct table_columns {
  size_t width = 3, radius = 0, rgb = 0;  // 0: not in the table
};
table_columns columns_of(const layout& l) {
  table_columns c;
  if (l.radius) c.radius = c.width++;
  if (l.rgb[0]) c.rgb = c.width, c.width += 3;
  return c;
}

using api::column;
// first's values in place, and the next components' at second's distance from them.
column file_column(const char* rows, const element& v, const property* first, const property* second, bool swap) {
  const ptrdiff_t component = second ? ptrdiff_t(second->offset) - ptrdiff_t(first->offset) : 0;
  const auto type = first->type == ply_type::f32   ? api::element::f32
                    : first->type == ply_type::f64 ? api::element::f64
                                                   : api::element::u8;
  return column{rows + first->offset, type, ptrdiff_t(v.row_bytes), component, swap};
}

// Whether three properties lie at even steps (x y z in a row), so one column reads them.
bool evenly_spaced(const property* const p[3]) {
  return !p[0] || p[1]->offset - p[0]->offset == p[2]->offset - p[1]->offset;
}

// A binary vertex element's checks, and its colour-by values (into `shown`).
void check_binary(const layout& l, const char* rows, uint64_t file_at, bool swap, std::vector<double>* shown) {
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
    if (shown) {
      const double x = value_at(row + l.color_by->offset, l.color_by->type, swap);
      check_value(role::shown, *l.color_by, k, x, at + l.color_by->offset);
      (*shown)[k] = x;
    }
  }
}

// Binary rows copied into the table (properties not evenly spaced, which one column cannot read).
void decode_binary(const layout& l, const char* rows, bool swap, ply_storage& st) {
  const table_columns tc = columns_of(l);
  const element& v = *l.vertex;
  st.table.resize(v.count * tc.width);
  for (uint64_t k = 0; k < v.count; ++k) {
    const char* row = rows + k * v.row_bytes;
    double* out = st.table.data() + k * tc.width;
    for (int c = 0; c < 3; ++c) {
      out[c] = value_at(row + l.xyz[c]->offset, l.xyz[c]->type, swap);
      if (tc.rgb) {
        const double x = value_at(row + l.rgb[c]->offset, l.rgb[c]->type, swap);
        out[tc.rgb + size_t(c)] = l.rgb[c]->type == ply_type::u8 ? x / 255.0 : x;
      }
    }
    if (tc.radius) out[tc.radius] = value_at(row + l.radius->offset, l.radius->type, swap);
  }
}

// Table columns as the view's: doubles, tc.width a row.
void view_table(const layout& l, ply_storage& st, api::sphere_arrays& view) {
  const table_columns tc = columns_of(l);
  const ptrdiff_t row = ptrdiff_t(tc.width * sizeof(double));
  view.centers = column{st.table.data(), api::element::f64, row, sizeof(double), false};
  if (tc.radius) view.radii = column{st.table.data() + tc.radius, api::element::f64, row, 0, false};
  if (tc.rgb) view.colors = column{st.table.data() + tc.rgb, api::element::f64, row, sizeof(double), false};
}

// The vertex element's rows in a binary body: read in place, or decoded.
void read_binary(const header& h, const layout& l, ply_storage& st, api::sphere_arrays& view, std::vector<double>* shown) {
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
  if (shown) shown->resize(v.count);
  check_binary(l, rows, h.bytes + at, swap, shown);
  if (!evenly_spaced(l.xyz) || !evenly_spaced(l.rgb)) {
    decode_binary(l, rows, swap, st);
    view_table(l, st, view);
    return;
  }
  view.centers = file_column(rows, v, l.xyz[0], l.xyz[1], swap);
  if (l.radius) view.radii = file_column(rows, v, l.radius, nullptr, swap);
  if (l.rgb[0]) view.colors = file_column(rows, v, l.rgb[0], l.rgb[1], swap);
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

// Where each vertex property of an ASCII row goes: a table column (or none)
// and what its value must be.
struct slot {
  int column = -1;
  role what = role::other;
  bool byte_color = false;  // uchar red green blue: value / 255
  bool shown = false;       // --color-by's property
};
std::vector<slot> slots_of(const layout& l) {
  const table_columns tc = columns_of(l);
  std::vector<slot> s(l.vertex->props.size());
  const auto index = [&](const property* p) { return size_t(p - l.vertex->props.data()); };
  for (int c = 0; c < 3; ++c) {
    s[index(l.xyz[c])] = {c, role::coordinate};
    if (l.rgb[0]) s[index(l.rgb[c])] = {int(tc.rgb) + c, role::color, l.rgb[c]->type == ply_type::u8};
  }
  if (l.radius) s[index(l.radius)] = {int(tc.radius), role::radius};
  if (l.color_by) s[index(l.color_by)].shown = true;
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

void read_ascii(const header& h, const layout& l, ply_storage& st, api::sphere_arrays& view, std::vector<double>* shown) {
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
  if (shown) shown->resize(v.count);
  for (uint64_t k = 0; k < v.count; ++k) {
    double* row = st.table.data() + k * width;
    for (size_t i = 0; i < slots.size(); ++i) {
      const std::string_view t = w.next();
      const property& p = v.props[i];
      if (t.empty()) fail("vertex", "the file ends after " + std::to_string(k) + " of " + std::to_string(v.count) + " vertices", w.offset(t));
      const slot& s = slots[i];
      if (s.column < 0 && !s.shown) continue;
      const std::string path = "vertex[" + std::to_string(k) + "]." + p.name;
      const double x = ascii_number(t, p.type, path, w.offset(t));
      check_value(s.what, p, k, x, w.offset(t));
      if (s.shown) check_value(role::shown, p, k, x, w.offset(t));
      if (s.shown) (*shown)[k] = x;
      if (s.column >= 0) row[s.column] = s.byte_color ? x / 255.0 : x;
    }
  }
  view_table(l, st, view);
}

// --color-by: each sphere's value through the colormap, 3 floats a sphere.
void color_by(const api::particles& o, const std::vector<double>& shown, ply_storage& st, api::sphere_arrays& view) {
  double lo = o.color_range ? (*o.color_range)[0] : INFINITY, hi = o.color_range ? (*o.color_range)[1] : -INFINITY;
  if (!o.color_range)
    for (double x : shown) lo = std::min(lo, x), hi = std::max(hi, x);
  st.colors.resize(shown.size() * 3);
  for (size_t k = 0; k < shown.size(); ++k) {
    const std::array<float, 3> c = colormap_color(colormap_named(o.colormap), shown[k], lo, hi);
    std::copy(c.begin(), c.end(), st.colors.begin() + ptrdiff_t(3 * k));
  }
  view.colors = column{st.colors.data(), api::element::f32, 3 * sizeof(float), sizeof(float), false};
}

// The body after the header, read once; a file that changes meanwhile is refused.
std::shared_ptr<ply_storage> read_body(const byte_source& src, const header& h) {
  auto st = std::make_shared<ply_storage>();
  st->body_bytes = size_t(src.size - h.bytes);
  st->mapped = std::max<size_t>(st->body_bytes, 1);
  // Huge pages always: the preparation reads it out of order (a TLB miss a
  // sphere costs more than the faults: 10^8 spheres 22 s, not 28 s).
  st->body = static_cast<char*>(exact_body ? std::malloc(st->mapped) : map_huge(st->mapped, true));
  if (!st->body) throw scene_file_error{"", "out of memory reading " + std::to_string(st->body_bytes) + " bytes", true};
  const ptrdiff_t got = src.read(h.bytes, st->body_bytes, st->body);
  if (got < 0) throw scene_file_error{"", std::strerror(errno), true};
  if (size_t(got) != st->body_bytes || !src.unchanged())
    throw scene_file_error{"", "changed while being read (it was " + std::to_string(src.size) + " bytes)"};
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

std::variant<scene_file_contents, scene_file_error> read_ply(const byte_source& src, const api::particles& o) try {
  std::string head(size_t(std::min<uint64_t>(src.size, max_ply_header_bytes)), '\0');
  const ptrdiff_t got = src.read(0, head.size(), head.data());
  if (got < 0) return scene_file_error{"", std::strerror(errno), true};
  head.resize(size_t(got));
  const header h = parse_header(head, src.size);
  const layout l = layout_of(h, o);
  const std::shared_ptr<ply_storage> st = read_body(src, h);
  api::sphere_arrays view;
  view.count = size_t(l.vertex->count);
  std::vector<double> shown;  // sized by the readers, once they know the file holds the count
  if (h.format == encoding::ascii) read_ascii(h, l, *st, view, l.color_by ? &shown : nullptr);
  else read_binary(h, l, *st, view, l.color_by ? &shown : nullptr);
  if (o.radius) {
    st->radius = *o.radius;
    view.radii = column{&st->radius, api::element::f64, 0, 0, false};
  }
  if (l.color_by) color_by(o, shown, *st, view);
  view.shade = view.colors.data ? shading::lit : shading::normal;
  view.owner = st;
  scene_file_contents c;
  c.scene.arrays = view;
  return c;
} catch (const ply_error& e) {
  return scene_file_error{e.path, e.message};
} catch (const scene_file_error& e) {
  return e;
}

std::variant<scene_file_contents, scene_file_error> read_ply_file(const std::string& path, const api::particles& o) {
  auto opened = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&opened)) return scene_file_error{"", *why, true};
  const regular_file& f = *std::get<std::unique_ptr<regular_file>>(opened);
  byte_source src;
  src.size = f.size();
  src.read = [&f](uint64_t offset, size_t n, char* to) { return f.read_at(offset, n, to); };
  src.unchanged = [&f] { return f.unchanged(); };
  return read_ply(src, o);
}

}  // namespace raycast
