// The fields of a text line (separated by spaces and tabs) and the numbers
// in them: decimal floating point by fast_float (Lemire's algorithm, exact
// to the last bit as strtod and at memory speed), whole numbers by the
// standard library's from_chars. Neither allocates nor looks at the locale.
#pragma once
#include <fast_float/fast_float.h>

#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace raycast::formats::input {

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The fields of a line, one after another.
class fields {
 public:
  explicit fields(std::string_view line) : p_(line.data()), end_(line.data() + line.size()) {}
  // The next field; false when the line has no more.
  bool next(std::string_view& field) {
    while (p_ < end_ && is_blank(*p_)) ++p_;
    if (p_ == end_) return false;
    const char* b = p_;
    while (p_ < end_ && !is_blank(*p_)) ++p_;
    field = std::string_view(b, size_t(p_ - b));
    return true;
  }
  // Whether only blanks are left.
  bool done() {
    while (p_ < end_ && is_blank(*p_)) ++p_;
    return p_ == end_;
  }
  const char* position() const { return p_; }
  const char* end() const { return end_; }

 private:
  const char* p_;
  const char* end_;
};

// A whole field as a double (nan and inf parse: the caller decides whether
// they are allowed); nullopt if it is not exactly one number. A leading '+'
// is taken, as strtod takes it.
inline std::optional<double> parse_double(std::string_view f) {
  const char* b = f.data();
  const char* e = b + f.size();
  if (b < e && *b == '+') ++b;
  double v = 0;
  const auto r = fast_float::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e || b == e) return std::nullopt;
  return v;
}

template <class Int>
inline std::optional<Int> parse_int(std::string_view f) {
  const char* b = f.data();
  const char* e = b + f.size();
  if (b < e && *b == '+') ++b;
  Int v = 0;
  const auto r = std::from_chars(b, e, v);
  if (r.ec != std::errc() || r.ptr != e || b == e) return std::nullopt;
  return v;
}

// A field quoted for an error message: at most 32 bytes of it, in quotes,
// each byte outside printable ASCII shown as '?'.
inline std::string quoted(std::string_view f) {
  std::string q = "'";
  for (char c : f.substr(0, 32)) q.push_back(c >= 0x20 && c < 0x7f ? c : '?');
  if (f.size() > 32) q.append("...");
  return q + "'";
}

}  // namespace raycast::formats::input
