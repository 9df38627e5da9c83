#include "settings/values.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "text/names.h"

namespace raycast {
namespace {

using vt = value_type;

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

// lo,hi in values, or pLO,pHI in percentiles (v.flag).
std::optional<std::string> parse_interval(std::string_view text, value& v, std::array<std::string, 3>& tokens) {
  std::array<std::string_view, 4> parts;
  if (auto e = split(text, 2, "number", "lo,hi or pLO,pHI", parts)) return e;
  const bool p0 = parts[0].starts_with('p'), p1 = parts[1].starts_with('p');
  if (p0 != p1) return quote_token(text) + ": give both ends as values or both as percentiles (p1,p99)";
  v.flag = p0;
  for (int k = 0; k < 2; ++k) {
    const std::string_view t = parts[size_t(k)].substr(p0 ? 1 : 0);
    if (auto e = parse_real(t, v.triple[size_t(k)])) return "number " + std::to_string(k + 1) + ": " + *e;
    tokens[size_t(k)] = parts[size_t(k)].substr(0, 64);
  }
  return std::nullopt;
}

// #rrggbb as r g b in [0, 1].
std::optional<std::string> parse_hex_color(std::string_view t, std::array<double, 3>& rgb) {
  unsigned c = 0;
  const auto [p, ec] = t.size() == 7 && t[0] == '#' ? std::from_chars(t.data() + 1, t.data() + 7, c, 16)
                                                     : std::from_chars_result{t.data(), std::errc::invalid_argument};
  if (ec != std::errc() || p != t.data() + 7) return quote_token(t) + " is not a colour (#rrggbb, as #1f77b4)";
  for (int k = 0; k < 3; ++k) rgb[size_t(k)] = double((c >> (16 - 8 * k)) & 0xff) / 255.0;
  return std::nullopt;
}

// NAME=VALUE,NAME=VALUE: a radius or a colour a type.
std::optional<std::string> parse_type_map(std::string_view text, bool colours,
                                          std::vector<std::pair<std::string, std::array<double, 3>>>& out) {
  const char* form = colours ? "NAME=#rrggbb,..." : "NAME=R,...";
  if (text.empty()) return std::string("empty value (want ") + form + ")";
  for (size_t start = 0; start <= text.size();) {
    const size_t end = std::min(text.find(',', start), text.size());
    const std::string_view item = text.substr(start, end - start);
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0)
      return quote_token(item) + " is not NAME=VALUE (want " + form + ")";
    std::array<double, 3> x{};
    const std::string_view rhs = item.substr(eq + 1);
    if (auto e = colours ? parse_hex_color(rhs, x) : parse_real(rhs, x[0])) return "type " + quote_token(item.substr(0, eq)) + ": " + *e;
    out.emplace_back(std::string(item.substr(0, eq)), x);
    start = end + 1;
  }
  return std::nullopt;
}

// K, or A:B[:S] with any of them left out.
std::optional<std::string> parse_frames(std::string_view text, value& v) {
  const auto part = [&](std::string_view t, std::optional<int64_t>& out) -> std::optional<std::string> {
    if (t.empty()) return std::nullopt;
    int64_t n = 0;
    if (auto e = parse_int(t, n)) return e;
    out = n;
    return std::nullopt;
  };
  const size_t c1 = text.find(':');
  if (c1 == std::string_view::npos) {
    if (auto e = part(text, v.first)) return e;
    if (!v.first) return std::string("empty value (want K or A:B[:S])");
    return std::nullopt;
  }
  const size_t c2 = text.find(':', c1 + 1);
  if (c2 != std::string_view::npos && text.find(':', c2 + 1) != std::string_view::npos)
    return quote_token(text) + " has more than three parts (want A:B[:S])";
  if (auto e = part(text.substr(0, c1), v.first)) return e;
  if (auto e = part(text.substr(c1 + 1, c2 == std::string_view::npos ? std::string_view::npos : c2 - c1 - 1), v.last))
    return e;
  std::optional<int64_t> step;
  if (c2 != std::string_view::npos)
    if (auto e = part(text.substr(c2 + 1), step)) return e;
  v.step = step.value_or(1);
  if (v.step == 0) return quote_token(text) + ": the step must not be 0";
  return std::nullopt;
}

}  // namespace

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

std::optional<std::string> parse_triple(std::string_view text, std::array<double, 3>& value,
                                        std::array<std::string, 3>* tokens) {
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

std::optional<std::string> parse_value(const setting& row, std::string_view text, value& v,
                                       std::array<std::string, 3>& tokens) {
  tokens[0] = text.substr(0, 64);
  switch (row.type) {
    case vt::integer:
    case vt::real: {
      // A number beyond a double (or an int64) is refused in the row's own
      // terms where it has a range ("too large (at most 16777216)").
      bool beyond = false;
      auto e = row.type == vt::integer ? parse_int(text, v.integer, &beyond) : parse_real(text, v.real, &beyond);
      const double x = row.type == vt::integer ? double(v.integer) : v.real;
      const double bound = x > 0 ? row.range.hi : row.range.lo;  // the bound it lies toward (either, for a zero)
      if (!beyond || (!std::isfinite(bound) && x != 0.0)) return e;
      return range_error(x, row.range, quote_token(text));
    }
    case vt::aspect: return parse_aspect(text, v.real);
    case vt::triple: return parse_triple(text, v.triple, &tokens);
    case vt::name: return parse_name(text, row.names, v.name, row.any_case);
    case vt::region: return parse_region(text, v.region);
    case vt::seed: return parse_seed(text, v.seed);
    case vt::text: v.text = std::string(text); return std::nullopt;
    case vt::interval: return parse_interval(text, v, tokens);
    case vt::type_map: return parse_type_map(text, row.id == setting_id::type_color, v.pairs);
    case vt::frames: return parse_frames(text, v);
    case vt::flag:  // the command line's bare option, or a keyword's true / false
      if (!text.empty() && text != "true" && text != "false") return quote_token(text) + " is not true or false";
      v.flag = text != "false";
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string> check_range(const setting& row, const value& v, const std::array<std::string, 3>& tokens) {
  switch (row.type) {
    case vt::integer: return range_error(double(v.integer), row.range, quote_token(tokens[0]));
    case vt::real:
    case vt::aspect: return range_error(v.real, row.range, quote_token(tokens[0]));
    case vt::triple:
      for (int k = 0; k < 3; ++k)
        if (auto e = range_error(v.triple[k], row.range, quote_token(tokens[size_t(k)])))
          return "component " + std::to_string(k + 1) + ": " + *e;
      return std::nullopt;
    case vt::interval:
      if (!(v.triple[0] < v.triple[1]))
        return quote_token(tokens[0]) + " is not below " + quote_token(tokens[1]) + " (want lo,hi with lo < hi)";
      if (v.flag && !(v.triple[0] >= 0.0 && v.triple[1] <= 100.0))
        return quote_token(tokens[0] + "," + tokens[1]) + ": percentiles lie from 0 to 100";
      return std::nullopt;
    case vt::type_map:
      for (const auto& [name, x] : v.pairs) {
        if (row.id == setting_id::type_color) continue;
        if (auto e = range_error(x[0], row.range, quote_token(number_text(x[0]))))
          return "type " + quote_token(name) + ": " + *e;
      }
      return std::nullopt;
    default: return std::nullopt;
  }
}

std::optional<std::string> select_frames(const value& v, size_t count, std::vector<size_t>& out) {
  const int64_t n = int64_t(count);
  out.clear();
  if (v.step == 0) {  // one index
    const int64_t k = *v.first < 0 ? *v.first + n : *v.first;
    if (k < 0 || k >= n)
      return std::to_string(*v.first) + " is beyond the file's " + std::to_string(n) + " frames (0 to " +
             std::to_string(n - 1) + ", or -" + std::to_string(n) + " to -1 from the end)";
    out.push_back(size_t(k));
    return std::nullopt;
  }
  // Python's slice.indices(): each end from the end where negative, clipped.
  const auto end = [&](std::optional<int64_t> e, int64_t fallback, int64_t lo, int64_t hi) {
    if (!e) return fallback;
    const int64_t k = *e < 0 ? *e + n : *e;
    return std::clamp(k, lo, hi);
  };
  const bool up = v.step > 0;
  const int64_t a = end(v.first, up ? 0 : n - 1, up ? 0 : -1, up ? n : n - 1);
  const int64_t b = end(v.last, up ? n : -1, up ? 0 : -1, up ? n : n - 1);
  for (int64_t k = a; up ? k < b : k > b; k += v.step) out.push_back(size_t(k));
  return std::nullopt;
}

}  // namespace raycast
