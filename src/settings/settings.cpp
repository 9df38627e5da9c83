#include "settings/settings.h"

#include "settings/names.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace raycast {
namespace {

constexpr size_t excerpt_bytes = 32;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr value_range positive{0.0, inf, true, false};
constexpr value_range dimension{1.0, double(max_dimension)};
constexpr value_range color{-max_color, max_color};

using enum setting_id;
using vt = value_type;

constexpr std::string_view projection_names[] = {"perspective", "orthographic"};  // enum projection's order

constexpr setting scene_rows[] = {
    {width, "--width", "-w", "camera.width", "width", vt::integer, dimension, {}, "N", "400", "Image width in pixels"},
    {height, "--height", "", "camera.height", "height", vt::integer, dimension, {}, "N",
     "int(width / aspect), at least 1", "Image height in pixels"},
    {aspect, "--aspect", "", "camera.aspect", "aspect", vt::aspect, positive, {}, "RATIO", "16:9",
     "Aspect ratio, W:H or a number"},
    {vfov, "--vfov", "", "camera.vfov", "vfov", vt::real, {0.0, 180.0, true, true}, {}, "DEGREES", "",
     "Vertical field of view in degrees, instead of --viewport-height", 1},
    {viewport_height, "--viewport-height", "", "camera.viewport_height", "viewport_height", vt::real, positive, {},
     "H", "2.0", "Viewport height in world units", 1},
    {focal_length, "--focal-length", "", "camera.focal_length", "focal_length", vt::real, positive, {}, "F", "1.0",
     "Distance from the origin to the viewport"},
    {setting_id::projection, "--projection", "", "camera.projection", "projection", vt::name, {}, projection_names,
     "NAME", "perspective",
     "perspective (rays from the camera) or orthographic (parallel rays from an image plane through lookfrom, "
     "--viewport-height high)"},
    {origin, "--origin", "", "", "", vt::triple, {}, {}, "X,Y,Z", "0,0,0", "Camera position", 2},
    {lookfrom, "--lookfrom", "", "camera.lookfrom", "lookfrom", vt::triple, {}, {}, "X,Y,Z", "",
     "Camera position (the same point as --origin)", 2},
    {lookat, "--lookat", "", "camera.lookat", "lookat", vt::triple, {}, {}, "X,Y,Z", "straight down -z",
     "Point the camera looks at"},
    {vup, "--vup", "", "camera.vup", "vup", vt::triple, {}, {}, "X,Y,Z", "0,1,0", "Which way is up for the camera"},
    {sky_bottom, "--sky-bottom", "", "sky.bottom", "sky_bottom", vt::triple, color, {}, "R,G,B", "1,1,1",
     "Colour looking straight down"},
    {sky_top, "--sky-top", "", "sky.top", "sky_top", vt::triple, color, {}, "R,G,B", "0.5,0.7,1.0",
     "Colour looking straight up"},
    {light, "--light", "", "light.direction", "light", vt::triple, {}, {}, "X,Y,Z", "a headlight",
     "Direction toward a directional light for lit spheres (instead of a light at the camera)"},
    {shadows, "--shadows", "", "light.shadows", "shadows", vt::flag, {}, {}, "", "off",
     "Hard shadows: a ray from each lit hit toward the --light"},
    {ao, "--ao", "", "ambient_occlusion.samples", "ao", vt::integer, {0.0, double(max_ao_samples)}, {}, "N", "0",
     "Ambient occlusion: rays per lit hit, cosine-weighted about the normal (0: none)"},
    {ao_distance, "--ao-distance", "", "ambient_occlusion.distance", "ao_distance", vt::real, positive, {}, "D",
     "unbounded", "How far an ambient occlusion ray looks for a sphere"},
};
static_assert(std::size(scene_rows) == scene_setting_count);

// A bound as a person writes it: 16777216, 180, 1e+30.
std::string number_text(double x) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, p) : std::to_string(x);
}

std::optional<std::string> range_error(double x, const value_range& r, const std::string& token) {
  if (x < r.lo || (r.lo_open && x == r.lo))
    return token + " is too small (" + (r.lo_open ? "above " : "at least ") + number_text(r.lo) + ")";
  if (x > r.hi || (r.hi_open && x == r.hi))
    return token + " is too large (" + (r.hi_open ? "below " : "at most ") + number_text(r.hi) + ")";
  return std::nullopt;
}

// Splits text at commas into exactly n parts ("component"s of "x,y,z"), or says how it does not.
std::optional<std::string> split(std::string_view text, size_t n, const char* noun, const char* form,
                                 std::array<std::string_view, 4>& parts) {
  size_t count = 0, start = 0;
  for (size_t k = 0; k <= text.size(); ++k) {
    if (k == text.size() || text[k] == ',') {
      if (count == n)
        return quote_token(text) + " has more than " + std::to_string(n) + " " + noun + "s (want " + form + ")";
      parts[count++] = text.substr(start, k - start);
      start = k + 1;
    }
  }
  if (count != n)
    return quote_token(text) + " has " + std::to_string(count) + " " + noun + "(s), want " + std::to_string(n) + " (" +
           form + ")";
  return std::nullopt;
}

}  // namespace

std::span<const setting> scene_settings() { return scene_rows; }

const setting* find_file_key(std::string_view file_key) {
  for (const setting& row : scene_rows)
    if (row.file_key == file_key) return &row;
  return nullptr;
}

std::string quote_token(std::string_view token) {
  size_t n = token.size();
  if (n > excerpt_bytes) {
    n = excerpt_bytes;
    while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xc0) == 0x80) --n;  // not inside a UTF-8 sequence
  }
  std::string r;
  r.reserve(n + 5);
  r.push_back('\'');
  r.append(token.data(), n);
  if (n < token.size()) r.append("\u2026");
  r.push_back('\'');
  return r;
}

std::optional<std::string> parse_int(std::string_view text, int64_t& value, bool* beyond) {
  if (text.empty()) return "empty value";
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc::result_out_of_range) {
    if (beyond) *beyond = true;
    const bool negative = text.front() == '-';
    value = negative ? std::numeric_limits<int64_t>::min() : std::numeric_limits<int64_t>::max();
    return quote_token(text) + (negative ? " is too small (at least " : " is too large (at most ") +
           std::to_string(value) + ")";
  }
  if (ec != std::errc() || p != end) return quote_token(text) + " is not an integer";
  return std::nullopt;
}

std::optional<std::string> parse_real(std::string_view text, double& value, bool* beyond) {
  if (text.empty()) return "empty value";
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (*begin == '+') ++begin;  // from_chars takes no plus sign
  auto [p, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) {
    // Beyond a double one way or the other: strtod says which (infinity or
    // zero), and so does the message -- a tiny number is not an overflow.
    if (beyond) *beyond = true;
    value = std::strtod(std::string(begin, end).c_str(), nullptr);
    if (std::isinf(value))
      return quote_token(text) + (value < 0 ? " is too small (below the lowest double, -1.8e308)"
                                            : " is too large (beyond the largest double, 1.8e308)");
    return quote_token(text) + " is too near 0 (nearer than the smallest double, 4.9e-324)";
  }
  if (ec != std::errc() || p != end || begin == end) return quote_token(text) + " is not a number";
  if (!std::isfinite(value)) return quote_token(text) + " is not a finite number";
  return std::nullopt;
}

std::optional<std::string> parse_aspect(std::string_view text, double& value) {
  const size_t colon = text.find(':');
  if (colon == std::string_view::npos) return parse_real(text, value);
  double w = 0, h = 0;
  if (auto e = parse_real(text.substr(0, colon), w)) return e;
  if (auto e = parse_real(text.substr(colon + 1), h)) return e;
  if (!(w > 0 && h > 0)) return quote_token(text) + ": both sides of W:H must be positive";
  value = w / h;
  if (!(value > 0) || !std::isfinite(value)) return quote_token(text) + " is not a finite positive ratio";
  return std::nullopt;
}

std::optional<std::string> parse_triple(std::string_view text, vec3& value, std::array<std::string, 3>* tokens) {
  std::array<std::string_view, 4> parts;
  if (auto e = split(text, 3, "component", "x,y,z", parts)) return e;
  for (int k = 0; k < 3; ++k) {
    double d = 0;
    if (auto e = parse_real(parts[k], d)) return "component " + std::to_string(k + 1) + ": " + *e;
    value[k] = d;
    if (tokens) (*tokens)[k] = parts[k].substr(0, 64);
  }
  return std::nullopt;
}

std::optional<std::string> parse_seed(std::string_view text, uint64_t& value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos)
    return quote_token(text) + " is not a whole number from 0 to 18446744073709551615";
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) return quote_token(text) + " is too large (at most 18446744073709551615)";
  return std::nullopt;
}

std::optional<std::string> parse_region(std::string_view text, std::array<int64_t, 4>& value) {
  std::array<std::string_view, 4> parts;
  if (auto e = split(text, 4, "number", "x0,y0,x1,y1", parts)) return e;
  for (size_t k = 0; k < 4; ++k)
    if (auto e = parse_int(parts[k], value[k])) return "number " + std::to_string(k + 1) + ": " + *e;
  return std::nullopt;
}

std::optional<std::string> check_region(const std::array<int64_t, 4>& r, int64_t width, int64_t height,
                                        std::string_view token) {
  if (!(0 <= r[0] && r[0] < r[2] && r[2] <= width))
    return "want 0 <= x0 < x1 <= " + std::to_string(width) + " (the image width), got " + quote_token(token);
  if (!(0 <= r[1] && r[1] < r[3] && r[3] <= height))
    return "want 0 <= y0 < y1 <= " + std::to_string(height) + " (the image height), got " + quote_token(token);
  return std::nullopt;
}

std::optional<std::string> parse_name(std::string_view text, std::span<const std::string_view> names,
                                      size_t& index, bool any_case) {
  const auto same = [&](std::string_view name) {
    if (!any_case) return name == text;
    return std::equal(name.begin(), name.end(), text.begin(), text.end(),
                      [](char a, char b) { return std::tolower((unsigned char)a) == std::tolower((unsigned char)b); });
  };
  for (index = 0; index < names.size(); ++index)
    if (same(names[index])) return std::nullopt;
  return not_one_of(text, quote_token(text), names);
}

std::optional<std::string> parse_value(const setting& row, std::string_view text, given& g) {
  g.tokens[0] = text.substr(0, 64);
  switch (row.type) {
    case vt::integer:
    case vt::real: {
      // A number beyond a double (or an int64) is refused in the row's own
      // terms where it has a range ("too large (at most 16777216)").
      bool beyond = false;
      auto e = row.type == vt::integer ? parse_int(text, g.v.integer, &beyond) : parse_real(text, g.v.real, &beyond);
      const double x = row.type == vt::integer ? double(g.v.integer) : g.v.real;
      const double bound = x > 0 ? row.range.hi : row.range.lo;  // the bound it lies toward (either, for a zero)
      if (!beyond || (!std::isfinite(bound) && x != 0.0)) return e;
      return range_error(x, row.range, quote_token(text));
    }
    case vt::aspect: return parse_aspect(text, g.v.real);
    case vt::triple: return parse_triple(text, g.v.triple, &g.tokens);
    case vt::name: return parse_name(text, row.names, g.v.name, row.any_case);
    case vt::region: return parse_region(text, g.v.region);
    case vt::seed: return parse_seed(text, g.v.seed);
    case vt::text: g.v.text = std::string(text); return std::nullopt;
    case vt::interval: {
      std::array<std::string_view, 4> parts;
      if (auto e = split(text, 2, "number", "lo,hi", parts)) return e;
      for (int k = 0; k < 2; ++k) {
        if (auto e = parse_real(parts[size_t(k)], g.v.triple[k])) return "number " + std::to_string(k + 1) + ": " + *e;
        g.tokens[size_t(k)] = parts[size_t(k)].substr(0, 64);
      }
      return std::nullopt;
    }
    case vt::flag:  // the command line's bare option, or a keyword's true / false
      if (!text.empty() && text != "true" && text != "false") return quote_token(text) + " is not true or false";
      g.v.flag = text != "false";
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string> check_range(const setting& row, const given& g) {
  switch (row.type) {
    case vt::integer: return range_error(double(g.v.integer), row.range, quote_token(g.tokens[0]));
    case vt::real:
    case vt::aspect: return range_error(g.v.real, row.range, quote_token(g.tokens[0]));
    case vt::triple:
      for (int k = 0; k < 3; ++k)
        if (auto e = range_error(g.v.triple[k], row.range, quote_token(g.tokens[size_t(k)])))
          return "component " + std::to_string(k + 1) + ": " + *e;
      return std::nullopt;
    case vt::interval:
      if (!(g.v.triple[0] < g.v.triple[1]))
        return quote_token(g.tokens[0]) + " is not below " + quote_token(g.tokens[1]) + " (want lo,hi with lo < hi)";
      return std::nullopt;
    default: return std::nullopt;
  }
}

std::optional<setting_error> check_groups(std::span<const setting> table, const settings& s) {
  for (size_t a = 0; a < table.size(); ++a) {
    if (table[a].group == 0 || !s.has(table[a].id)) continue;
    for (size_t b = a + 1; b < table.size(); ++b) {
      if (table[b].group != table[a].group || !s.has(table[b].id)) continue;
      const given& later = *s[table[b].id];
      const bool file = !later.where.empty() || later.source == table[b].file_key;
      const auto spell = [&](const setting& r) { return std::string(file ? r.file_key.substr(r.file_key.find('.') + 1) : r.option); };
      return setting_error{&table[b], later.source,
                           "give " + spell(table[a]) + " or " + spell(table[b]) + ", not both" + later.where};
    }
  }
  return std::nullopt;
}

void merge(settings& base, const settings& over, std::span<const setting> table) {
  for (const setting& row : table) {
    if (!over.has(row.id)) continue;
    if (row.group != 0)
      for (const setting& other : table)
        if (other.group == row.group) base[other.id].reset();
  }
  for (size_t k = 0; k < setting_count; ++k)
    if (over.at[k]) base.at[k] = over.at[k];
}

// A setting that means nothing for an orthographic camera (its rays are
// parallel: no field of view, no focal length), refused naming both.
std::optional<setting_error> meaningless_for_orthographic(const settings& s) {
  const auto row_of = [](setting_id id) { return &*std::find_if(std::begin(scene_rows), std::end(scene_rows), [id](const setting& r) { return r.id == id; }); };
  for (setting_id id : {vfov, focal_length}) {
    if (!s.has(id)) continue;
    const given& g = *s[id];
    const std::string by = s.has(setting_id::projection) ? s[setting_id::projection]->source : "camera.projection";
    return setting_error{row_of(id), g.source,
                         "means nothing with " + by +
                             " orthographic (its rays are parallel; the image plane is --viewport-height high)" +
                             g.where};
  }
  return std::nullopt;
}

std::optional<setting_error> resolve(const settings& s, camera_params& cp, sky& sk, lighting& li) {
  for (const setting& row : scene_rows)
    if (s.has(row.id))
      if (auto e = check_range(row, *s[row.id])) return setting_error{&row, s[row.id]->source, *e + s[row.id]->where};
  const auto get = [&](setting_id id) -> const value* { return s.has(id) ? &s[id]->v : nullptr; };
  if (auto v = get(width)) cp.image_width = v->integer;
  if (auto v = get(height)) cp.image_height = v->integer;
  if (auto v = get(setting_id::aspect)) cp.aspect_ratio = v->real;
  if (auto v = get(viewport_height)) {
    cp.viewport_height = v->real;
    cp.vfov_degrees.reset();
  }
  if (auto v = get(vfov)) cp.vfov_degrees = v->real;
  if (auto v = get(focal_length)) cp.focal_length = v->real;
  if (auto v = get(setting_id::projection)) cp.proj = raycast::projection(v->name);
  if (cp.proj == raycast::projection::orthographic)
    if (auto e = meaningless_for_orthographic(s)) return e;
  if (auto v = get(origin)) cp.origin = v->triple;
  if (auto v = get(lookfrom)) cp.origin = v->triple;
  if (auto v = get(lookat)) cp.lookat = v->triple;
  if (auto v = get(vup)) {
    cp.vup = v->triple;
    // Derived after merging: the lesson's view from wherever the camera ended up.
    if (!cp.lookat) cp.lookat = cp.origin + vec3(0.0, 0.0, -1.0);
  }
  if (auto v = get(sky_bottom)) sk.bottom = v->triple;
  if (auto v = get(sky_top)) sk.top = v->triple;
  if (auto v = get(light)) li.direction = v->triple;
  if (auto v = get(shadows)) li.shadows = v->flag;
  if (auto v = get(ao)) li.ao_samples = uint32_t(v->integer);
  if (auto v = get(ao_distance)) li.ao_distance = v->real;
  return std::nullopt;
}

}  // namespace raycast
