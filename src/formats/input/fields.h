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

// A space or a tab, \v, \f, \r (and \n, which a line never holds): two compares.
inline bool is_blank(char c) { return c == ' ' || unsigned(c - '\t') <= unsigned('\r' - '\t'); }

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

// The number at p (before e) into v, and the byte after it; nullptr where
// none begins at p. nan and inf parse: the caller decides whether they are
// allowed. A leading '+' is taken, as strtod takes it. Decimals without an
// exponent of at most 15 digits (what simulation codes write: LAMMPS's %g,
// ASE's %.8f) take Clinger's fast path: the digits m < 2^53 and 10^d (d <= 15)
// are exact doubles, so m / 10^d is the correctly rounded value, as fast_float
// (and strtod) gives it; everything else is fast_float's.
inline const char* parse_number(const char* p, const char* e, double& v) {
  static constexpr double tens[16] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const char* b = p + (p < e && *p == '+' ? 1 : 0);
  const char* q = b + (b < e && *b == '-' ? 1 : 0);
  uint64_t m = 0;
  int digits = 0, decimals = 0;
  for (; q < e && unsigned(*q - '0') < 10; ++q, ++digits) m = m * 10 + unsigned(*q - '0');
  if (q < e && *q == '.') {
    const char* f = ++q;
    for (; q < e && unsigned(*q - '0') < 10; ++q) m = m * 10 + unsigned(*q - '0');
    decimals = int(q - f);
    digits += decimals;
  }
  if (digits > 0 && digits <= 15 && (q == e || is_blank(*q))) {
    v = double(m) / tens[decimals];
    if (*b == '-') v = -v;
    return q;
  }
  const auto r = fast_float::from_chars(b, e, v);
  return r.ec == std::errc() && b < e ? r.ptr : nullptr;
}

// The common decimal at p (an optional '-', at most 7 digits, an optional
// '.' and at most 7 more, then a blank or e) into v, read eight bytes at a
// time as fast_float reads long mantissas (its eight-digit steps), with no
// branch per digit: one word where the number (dot included) fits in eight
// bytes, as most do, else a word for each side of the dot. Its value is
// Clinger's, as parse_number's, and always finite. nullptr for anything else (longer, an exponent, nan, not a
// number): parse_number's then. For a line_cursor's lines, which have
// line_padding readable bytes after them (p < e).
inline const char* parse_decimal_padded(const char* p, const char* e, double& v) {
  using fast_float::parse_eight_digits_unrolled;
  static constexpr double tens[8] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7};
  static constexpr uint32_t powers[8] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
  constexpr uint64_t zeros = 0x3030303030303030ull, highs = 0x8080808080808080ull;
  // The digits at q: how many lead (0 to 7; 8 if eight or more) and their value.
  const auto digits = [e](const char* q, uint32_t& value) {
    const uint64_t w = fast_float::read_u64(q);
    uint64_t flags = ((w + 0x4646464646464646ull) | (w - zeros)) & highs;  // the first non-digit's is exact
    if (e - q < 8) flags |= highs << (8 * (e - q));
    if (!flags) return 8;
    const int n = __builtin_ctzll(flags) / 8;
    value = n == 0 ? 0 : parse_eight_digits_unrolled((w << (8 * (8 - n))) | (zeros >> (8 * n)));
    return n;
  };
  const bool negative = *p == '-';
  const char* q = p + (negative ? 1 : 0);
  if (q < e) {  // a number of at most eight bytes, dot included (most are): one word
    const uint64_t w = fast_float::read_u64(q);
    const uint64_t x = w & ~highs, ascii = ~w & highs;  // per byte, without carries between bytes
    const uint64_t digit = ((x + 0x5050505050505050ull) & ~(x + 0x4646464646464646ull)) & ascii & highs;
    const uint64_t t = w ^ 0x2E2E2E2E2E2E2E2Eull;
    const uint64_t dot = ~(((t & ~highs) + ~highs) | t) & highs;
    uint64_t ok = digit | dot;
    if (e - q < 8) ok &= ~(highs << (8 * (e - q)));
    const int end = ok == highs ? 8 : __builtin_ctzll(~ok & highs) / 8;  // the first byte of neither
    const uint64_t dots = end == 8 ? dot : dot & ((uint64_t(1) << (8 * end)) - 1);
    const int n = end - (dots ? 1 : 0);
    if (n > 0 && (dots & (dots - 1)) == 0 && (q + end == e || is_blank(q[end]))) {
      uint64_t packed = w;
      int f = 0;
      if (dots) {  // the bytes after the dot one place down
        const int d = __builtin_ctzll(dots) / 8;
        const uint64_t below = (uint64_t(1) << (8 * d)) - 1;
        packed = (w & below) | ((w >> 8) & ~below);
        f = end - d - 1;
      }
      packed = n == 8 ? packed : (packed << (8 * (8 - n))) | (zeros >> (8 * n));
      v = double(parse_eight_digits_unrolled(packed)) / tens[f];
      if (negative) v = -v;
      return q + end;
    }
  }
  uint32_t whole = 0, fraction = 0;
  const int n = q < e ? digits(q, whole) : 0;
  int f = 0;
  const char* end = q + n;
  if (n < 8 && end < e && *end == '.') {
    f = end + 1 < e ? digits(end + 1, fraction) : 0;
    end += 1 + f;
  }
  if (n == 8 || f == 8 || n + f == 0 || (end < e && !is_blank(*end))) return nullptr;
  v = double(uint64_t(whole) * powers[f] + fraction) / tens[f];
  if (negative) v = -v;
  return end;
}

// A whole field as a double; nullopt if it is not exactly one number.
inline std::optional<double> parse_double(std::string_view f) {
  const char* e = f.data() + f.size();
  double v = 0;
  const char* end = parse_number(f.data(), e, v);
  if (!end || end != e) return std::nullopt;
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

// Bytes of a file shown in an error message: at most `most` of them, each
// outside printable ASCII as '?', so that a message stays one line.
inline std::string printable(std::string_view f, size_t most = 64) {
  std::string q;
  for (char c : f.substr(0, most)) q.push_back(c >= 0x20 && c < 0x7f ? c : '?');
  if (f.size() > most) q.append("...");
  return q;
}

// A field quoted for an error message: at most 32 bytes of it, printable.
inline std::string quoted(std::string_view f) {
  std::string q(1, '\'');
  q += printable(f, 32);
  q += '\'';
  return q;
}

}  // namespace raycast::formats::input
