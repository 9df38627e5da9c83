#include "formats/json.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <utility>
#include <vector>

#include <simdjson.h>

#include "memory/arrays.h"
#include "settings/names.h"
#include "formats/regular_file.h"

namespace raycast {
namespace {

namespace od = simdjson::ondemand;
using simdjson::error_code;

// simdjson's On-Demand parser indexes the input with 32-bit offsets.
static_assert(max_scene_file_bytes <= simdjson::SIMDJSON_MAXSIZE_BYTES);

// A scene nests four levels deep ({"spheres": [{"center": [...]}]}). The
// reader refuses deeper input itself, at the first level the format does not
// have (a value of the wrong type), so nesting costs nothing however deep;
// simdjson is given a small bound as well (its On-Demand front end checks it
// only in development builds).
constexpr size_t max_depth = 32;

// How much of the offending input an error quotes.
constexpr size_t excerpt_bytes = 32;

// Thrown inside the reader only; the public functions turn it into their result.
struct failure {
  scene_file_error e;
};
// Thrown instead by a reader of one window of a large text (read_windowed),
// whose errors are never reported: the whole text is parsed again for them.
struct window_failed {};

// The spheres array left out of a skeleton text (read_windowed): the reader
// of the skeleton reports places after it as they are in the whole text.
struct text_gap {
  const char* at = nullptr;  // in the skeleton: just after the array's '['
  size_t bytes = 0;          // left out there
  size_t lines = 0;          // newlines among them
  size_t tail = 0;           // bytes after the last of them (all, if none)
  // The whole text's first bytes from `at` on (up to quote_span), for quotes
  // that start just before the gap and run into it.
  std::string_view head;

  // Bytes [from, to) of the array left out, their newlines counted.
  void pass(const char* from, const char* to) {
    bytes += size_t(to - from);
    tail += size_t(to - from);
    for (const char* p = from; (p = static_cast<const char*>(std::memchr(p, '\n', size_t(to - p)))); ++p) {
      ++lines;
      tail = size_t(to - p - 1);
    }
  }
};
constexpr size_t quote_span = 64;

// The input, padded as simdjson needs (SIMDJSON_PADDING readable bytes after
// the text), freed when the parse returns. A big text is mapped rather than
// allocated, so that its pages stay untouched until the text is read into
// them and can be handed back as the parse passes them (mapped()); a small
// one comes from the heap, whose pages a long-lived caller (the library, the
// bench) reuses rather than faulting in fresh ones for every file.
class padded_text {
 public:
  static constexpr size_t mapped_from = size_t(16) << 20;

  // Room for n bytes and the padding, or nullopt.
  static std::optional<padded_text> allocate(size_t n) {
    padded_text t;
    t.capacity_ = n + simdjson::SIMDJSON_PADDING;
    if (t.capacity_ < mapped_from) {
      t.data_ = static_cast<char*>(std::malloc(t.capacity_));
      if (!t.data_) return std::nullopt;
      return t;
    }
    void* p = map_huge(t.capacity_);
    if (!p) return std::nullopt;
    t.data_ = static_cast<char*>(p);
    return t;
  }
  padded_text(padded_text&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(o.size_), capacity_(o.capacity_) {}
  padded_text& operator=(padded_text&&) = delete;
  ~padded_text() {
    if (!data_) return;
    if (mapped()) unmap_huge(data_, capacity_);
    else std::free(data_);
  }

  bool mapped() const { return capacity_ >= mapped_from; }
  char* data() const { return data_; }
  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  // The text is the first n bytes; the padding after it is zeros.
  void finish(size_t n) {
    size_ = n;
    std::memset(data_ + n, 0, capacity_ - n);
  }

 private:
  padded_text() = default;
  char* data_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

std::string bytes_text(uint64_t n) { return std::to_string(n) + " bytes"; }

scene_file_error too_large(uint64_t n) {
  return {"", "is " + bytes_text(n) + "; a scene file may be at most 4 GiB - 1 (" + bytes_text(max_scene_file_bytes) + ")"};
}

// A short quote of the input at a place: the token there (a number, string or
// word), or the rest of the line from an object or array, cut at a character
// boundary with "…" when longer than excerpt_bytes.
std::string excerpt(std::string_view rest) {
  size_t n = 0;
  const bool container = !rest.empty() && std::string_view("{[,:]}").find(rest[0]) != std::string_view::npos;
  const bool string = !rest.empty() && rest[0] == '"';
  const auto token_end = [&](size_t k) {
    if (container) return false;
    if (string) return k > 0 && rest[k - 1] == '"' && (k > 1 && rest[k - 2] != '\\');
    return std::string_view(",:]} \t").find(rest[k]) != std::string_view::npos;
  };
  while (n < rest.size() && n <= excerpt_bytes && rest[n] != '\n' && rest[n] != '\r' && !token_end(n)) ++n;
  if (n <= excerpt_bytes) return std::string(rest.substr(0, n));
  n = excerpt_bytes;
  while (n > 0 && (static_cast<unsigned char>(rest[n]) & 0xc0) == 0x80) --n;  // not inside a UTF-8 sequence
  return std::string(rest.substr(0, n)) + "\u2026";
}

std::string json_error(error_code e) {
  switch (e) {
    case simdjson::TAPE_ERROR: return "a missing or extra comma, colon, brace, bracket or key";
    case simdjson::INCOMPLETE_ARRAY_OR_OBJECT: return "an object or array is not closed";
    case simdjson::TRAILING_CONTENT: return "more after the scene's object";
    case simdjson::UNCLOSED_STRING: return "a string is not closed";
    case simdjson::STRING_ERROR: return "a string has a bad escape or an unescaped control character";
    case simdjson::UNESCAPED_CHARS: return "a string has an unescaped control character";
    case simdjson::UTF8_ERROR: return "not UTF-8";
    case simdjson::T_ATOM_ERROR:
    case simdjson::F_ATOM_ERROR:
    case simdjson::N_ATOM_ERROR: return "a word that is not true, false or null";
    case simdjson::EMPTY: return "no JSON value, the file is empty";
    case simdjson::DEPTH_ERROR: return "nested deeper than " + std::to_string(max_depth) + " levels";
    case simdjson::MEMALLOC: return "out of memory";
    default: return simdjson::error_message(e);
  }
}

bool json_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

// Whether text is a number as JSON writes it: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
bool json_number(std::string_view t) {
  size_t k = 0;
  const auto digits = [&] {
    const size_t from = k;
    while (k < t.size() && t[k] >= '0' && t[k] <= '9') ++k;
    return k > from;
  };
  if (k < t.size() && t[k] == '-') ++k;
  if (k < t.size() && t[k] == '0') ++k;
  else if (!digits()) return false;
  if (k < t.size() && t[k] == '.' && (++k, !digits())) return false;
  if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
    ++k;
    if (k < t.size() && (t[k] == '+' || t[k] == '-')) ++k;
    if (!digits()) return false;
  }
  return k == t.size();
}

// The first place where a text breaks JSON's grammar, and why in plain
// terms. simdjson's On-Demand parser says where its iterator got to, which
// after a syntax error can be far past it (array::count_elements, meeting a
// comma too many or too few in the spheres array, leaves it at the end of
// the text), and says it in its own terms ("a missing or extra comma, colon,
// brace, bracket or key"); its syntax errors are placed by this scan instead.
struct syntax_fault {
  const char* at;
  std::string why;
};

// A container open where the scan starts or met on the way: '{' or '[', and
// where (nullptr: before the scan's start; the end of the text is named).
struct open_bracket {
  char kind;
  const char* at;
};

// Whether c can start a JSON value.
bool starts_value(char c) {
  return std::string_view("{[\"-tfn").find(c) != std::string_view::npos || (c >= '0' && c <= '9');
}

// The end of the scalar at p (a string, number or word), or nullptr and why.
const char* scalar_end(const char* p, const char* end, std::string& why) {
  if (*p == '"') {
    for (const char* q = p + 1; q < end; ++q) {
      if (*q == '\\') {
        ++q;
      } else if (*q == '"') {
        return q + 1;
      } else if (static_cast<unsigned char>(*q) < 0x20) {
        why = *q == '\n' || *q == '\r' ? "a string is not closed on its line"
                                     : "a string has an unescaped control character";
        return nullptr;
      }
    }
    why = "a string is not closed";
    return nullptr;
  }
  const char* q = p;
  while (q < end && !json_space(*q) && std::string_view(",:[]{}\"").find(*q) == std::string_view::npos) ++q;
  const std::string_view token(p, size_t(q - p));
  if (token == "true" || token == "false" || token == "null" || json_number(token)) return q;
  if (*p == '-' || (*p >= '0' && *p <= '9')) why = quote_token(token) + " is not a JSON number";
  else if (std::isalpha(static_cast<unsigned char>(*p))) why = "a word that is not true, false or null";
  else why = "expected a value";
  return nullptr;
}

// After a value in the innermost of open (or at the end of the text): a
// comma, the container's close, or nothing more. p at the token.
enum class expect { value, key, colon, next };
std::optional<syntax_fault> after_value(const char*& p, const char* end, std::vector<open_bracket>& open,
                                        expect& want, const char*& comma) {
  if (open.empty()) return syntax_fault{p, "more after the scene's object"};
  const bool array = open.back().kind == '[';
  if (*p == ',') {
    comma = p++;
    want = array ? expect::value : expect::key;
    return std::nullopt;
  }
  if (*p == (array ? ']' : '}')) {
    open.pop_back();
    ++p;
    return std::nullopt;
  }
  if (*p == (array ? '}' : ']'))
    return syntax_fault{p, array ? "expected ']' to close the array before this '}'"
                                 : "expected '}' to close the object before this ']'"};
  if (!array)
    return syntax_fault{p, *p == '"' ? "a comma is missing before this key" : "expected a comma or '}' after a value"};
  if (!starts_value(*p)) return syntax_fault{p, "expected a comma or ']' after a value"};
  // A string followed by a colon is a key: the array before it never closed.
  std::string why;
  const char* q = *p == '"' ? scalar_end(p, end, why) : nullptr;
  while (q && q < end && json_space(*q)) ++q;
  if (q && q < end && *q == ':') return syntax_fault{p, "expected ']' to close the array before this key"};
  return syntax_fault{p, "a comma is missing before this value"};
}

// The first syntax error from p on, where a value is expected inside the
// containers open (outermost first), or nullopt when the text to end is JSON.
std::optional<syntax_fault> first_syntax_error(const char* p, const char* end, std::vector<open_bracket> open) {
  expect want = expect::value;
  const char* comma = nullptr;  // the comma just passed, while the next token is looked for
  std::string why;
  while (p < end) {
    if (json_space(*p)) {
      ++p;
      continue;
    }
    const char c = *p;
    if (want == expect::next) {
      if (auto f = after_value(p, end, open, want, comma)) return f;
      continue;
    }
    if (want == expect::colon) {
      if (c != ':') return syntax_fault{p, "expected a colon after the key"};
      ++p;
      want = expect::value;
      continue;
    }
    const char* const after_comma = std::exchange(comma, nullptr);
    if (want == expect::key && c != '"') {
      if (after_comma && (c == '}' || c == ',')) return syntax_fault{after_comma, "a comma with no key after it"};
      return syntax_fault{p, "expected a key in double quotes"};
    }
    if (after_comma && (c == ']' || c == ',')) return syntax_fault{after_comma, "a comma with no value after it"};
    if (c == '{' || c == '[') {  // opened, and closed at once when empty
      open.push_back({c, p});
      for (++p; p < end && json_space(*p);) ++p;
      want = c == '{' ? expect::key : expect::value;
      if (p < end && *p == (c == '{' ? '}' : ']')) {
        open.pop_back();
        ++p;
        want = expect::next;
      }
      continue;
    }
    if (want == expect::value && !starts_value(c) && !std::isalpha(static_cast<unsigned char>(c)))
      return syntax_fault{p, "expected a value"};
    const char* const q = scalar_end(p, end, why);
    if (!q) return syntax_fault{p, why};
    p = q;
    want = want == expect::key ? expect::colon : expect::next;
  }
  if (!open.empty())
    return syntax_fault{open.back().at ? open.back().at : end,
                        open.back().kind == '{' ? "an object is not closed" : "an array is not closed"};
  if (want != expect::next) return syntax_fault{end, "expected a value"};
  return std::nullopt;
}

class reader {
 public:
  // text: memory of ours (padded_text); page-aligned and released as it is
  // read when `release`.
  reader(const char* text, size_t size, bool release, od::document& doc)
      : text_(text), size_(size), release_(release), doc_(doc), released_to_(text), released_line_start_(text) {}

  scene_file_contents read();

  // A skeleton's reader (places after `gap` as in the whole text), or a
  // window's (failures thrown as window_failed).
  void skeleton_of(const text_gap& gap) { gap_ = gap; }
  void window() { quiet_ = true; }

  // An error of the text's index (stage one), with the place the scan finds.
  [[noreturn]] void fail_index(error_code e) const { fail_syntax(e, nullptr); }

  // The spheres of a window ("[" + whole spheres + "]"), numbered on from k,
  // up to the first that fails; the place after the last one read (its ','
  // or ']'), or nullptr when none was.
  const char* read_window(std::vector<sphere>& out, size_t& k);

 private:
  using keys = std::span<const std::string_view>;

  // " (at line L, column C: excerpt)" for a place in the text; columns count bytes.
  std::string where(const char* at) const {
    if (at == nullptr || at < released_to_ || at > text_ + size_) return "";
    // Lines counted on from the last place asked for when it is before this
    // one (the camera and sky keys of a file of millions of spheres each
    // ask), else from the end of the text handed back, counted as it went.
    if (at < counted_) {
      counted_ = released_to_;
      line_ = released_lines_ + 1;
      line_start_ = released_line_start_;
    }
    for (const char* p = counted_; (p = static_cast<const char*>(std::memchr(p, '\n', size_t(at - p)))); ++p) {
      ++line_;
      line_start_ = p + 1;
    }
    counted_ = at;
    size_t line = line_, column = size_t(at - line_start_) + 1;
    if (gap_.at && at >= gap_.at) {  // a skeleton's place after its gap
      if (line_start_ <= gap_.at) column = gap_.lines ? gap_.tail + size_t(at - gap_.at) + 1 : column + gap_.bytes;
      line += gap_.lines;
    }
    std::string r = " (at line " + std::to_string(line) + ", column " + std::to_string(column);
    std::string_view rest(at, size_t(text_ + size_ - at));
    std::string joined;
    if (gap_.at && at < gap_.at && size_t(gap_.at - at) < quote_span) {  // as in the whole text
      joined = std::string(at, gap_.at) + std::string(gap_.head);
      rest = joined;
    }
    std::string quote = excerpt(rest);
    while (!quote.empty() && (quote.back() == ' ' || quote.back() == '\t')) quote.pop_back();
    if (!quote.empty()) r += ": " + quote;
    return r + ")";
  }

  // Hands the pages of text well behind `cursor` back to the system, counting
  // their lines first (where() needs them): the spheres then fill memory as
  // the text they came from leaves it, and a big file's peak is its text plus
  // simdjson's index rather than that plus every sphere. The iterator never
  // reads text behind it again; a 1 MiB margin keeps the current token whole.
  void release_text_before(const char* cursor) {
    constexpr size_t page = huge_page_bytes, margin = size_t(1) << 20, step = size_t(8) << 20;
    if (!release_ || cursor < released_to_ + margin + step) return;
    const uintptr_t to = (reinterpret_cast<uintptr_t>(cursor) - margin) & ~uintptr_t(page - 1);
    const char* end = reinterpret_cast<const char*>(to);
    for (const char* p = released_to_; (p = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)))); ++p) {
      ++released_lines_;
      released_line_start_ = p + 1;
    }
    ::madvise(const_cast<char*>(released_to_), size_t(end - released_to_), MADV_DONTNEED);
    released_to_ = end;
    if (counted_ < end) {  // where() counts on from here
      counted_ = end;
      line_ = released_lines_ + 1;
      line_start_ = released_line_start_;
    }
  }

  // Where the iterator stands, for errors simdjson reports without a value.
  const char* here() {
    const char* at = nullptr;
    if (doc_.current_location().get(at) != simdjson::SUCCESS) return nullptr;
    return at;
  }

  // An error about the value at `at`. Where no value stands there ("[1,,2]",
  // "[1,]", "{"a": }", a stray character), a syntax error instead.
  [[noreturn]] void fail(std::string path, const std::string& why, const char* at) const {
    if (quiet_) throw window_failed{};
    if (at && !starts_value(*at)) fail_syntax(simdjson::TAPE_ERROR, at);
    throw failure{{std::move(path), why + where(at)}};
  }

  // Input simdjson refuses: a file error (empty path), as the JSON is not a
  // scene at all. A syntax error is reported where the text first breaks the
  // grammar (first_syntax_error), not where simdjson's iterator got to.
  [[noreturn]] void fail_json(error_code e, const char* at) const {
    if (e == simdjson::TAPE_ERROR || e == simdjson::INCOMPLETE_ARRAY_OR_OBJECT || e == simdjson::TRAILING_CONTENT)
      fail_syntax(e, at);
    fail_json(json_error(e), at);
  }
  [[noreturn]] void fail_syntax(error_code e, const char* at) const {
    if (quiet_) throw window_failed{};
    // From the start of the text, or from a sphere whose text before was
    // handed back (release_text_before): inside the root object's spheres array.
    std::vector<open_bracket> open;
    if (scan_from_) open = {{'{', nullptr}, {'[', nullptr}};
    if (auto f = first_syntax_error(scan_from_ ? scan_from_ : text_, text_ + size_, std::move(open)))
      throw failure{{"", "not valid JSON: " + f->why + where(f->at)}};
    throw failure{{"", "not valid JSON: " + json_error(e) + where(at)}};
  }
  [[noreturn]] void fail_json(const std::string& why, const char* at) const {
    if (quiet_) throw window_failed{};
    if (at && !starts_value(*at)) fail_syntax(simdjson::TAPE_ERROR, at);
    throw failure{{"", "not valid JSON: " + why + where(at)}};
  }

  const char* at(od::value& v) { return v.raw_json_token().data(); }

  // v as an object, or an error naming path.
  template <class Path>
  od::object object(od::value& v, const Path& path) {
    const char* start = at(v);
    od::object obj;
    if (error_code e = v.get_object().get(obj)) {
      if (e == simdjson::INCORRECT_TYPE) fail(path(), "must be an object", start);
      fail_json(e, start);
    }
    return obj;
  }

  // v as an array, or the error why (naming path).
  template <class Path>
  od::array array(od::value& v, const Path& path, const char* why) {
    const char* start = at(v);
    od::array arr;
    if (error_code e = v.get_array().get(arr)) {
      if (e == simdjson::INCORRECT_TYPE) fail(path(), why, start);
      fail_json(e, start);
    }
    return arr;
  }

  // Calls f(index of the key in known, its value) for each field of obj,
  // refusing unknown and repeated keys.
  template <class Path, class F>
  void fields(od::object obj, const Path& path, keys known, F&& f) {
    uint32_t seen = 0;
    for (auto result : obj) {
      // The field in place (a copy of it stalls on store forwarding).
      if (error_code e = result.error()) fail_json(e, here());
      od::field& fld = result.value_unsafe();
      const char* key_at = fld.key().raw() - 1;  // the opening quote
      // A key without escapes is its raw text (stage one checked that a
      // closing quote exists); only others are unescaped.
      std::string_view key(key_at + 1, 0);
      while (key.data()[key.size()] != '"' && key.data()[key.size()] != '\\') key = {key.data(), key.size() + 1};
      if (key.data()[key.size()] == '\\')
        if (error_code e = fld.unescaped_key().get(key)) fail_json(e, key_at);
      int index = 0;
      for (std::string_view k : known) {
        if (k == key) break;
        ++index;
      }
      if (index == int(known.size())) {
        std::string list;
        for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(child(path(), excerpt(key)), "unknown key (known here: " + list + ")" + did_you_mean(key, known), key_at);
      }
      if (seen & (1u << index)) fail(child(path(), key), "duplicate key", key_at);
      seen |= 1u << index;
      od::value& value = fld.value();
      f(index, value);
    }
  }

  static std::string child(const std::string& parent, std::string_view key) {
    return parent.empty() ? std::string(key) : parent + "." + std::string(key);
  }

  template <class Path>
  double number(od::value& v, const Path& path) {
    double x = 0;
    if (error_code e = v.get_double().get(x)) {
      const char* where_at = at(v);
      od::json_type t;
      if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", where_at);
      if (t != od::json_type::number) fail(path(), "must be a number", where_at);
      fail(path(), "is not a JSON number within a double's range (about +-1.8e308)", where_at);
    }
    return x;  // JSON has no infinities or NaN
  }

  template <class Path>
  vec3 triple(od::value& v, const Path& path) {
    const char* start = at(v);
    od::array arr = array(v, path, "must be an array of 3 numbers");
    vec3 r(0.0);
    int n = 0;
    for (auto result : arr) {
      if (error_code e = result.error()) fail_json(e, here());
      od::value& el = result.value_unsafe();  // in place, as in fields()
      // A fourth element, or a syntax error there ("[1, 2, 3,]": fail()).
      if (n == 3) fail(path(), "must be an array of 3 numbers", starts_value(*at(el)) ? start : at(el));
      r[n] = number(el, [&] { return path() + "[" + std::to_string(n) + "]"; });
      ++n;
    }
    if (n != 3) fail(path(), "must be an array of 3 numbers", start);
    return r;
  }

  void read_spheres(od::value& v, std::vector<sphere>& out);
  sphere read_sphere(od::value& item, size_t k);

  // The camera and sky keys as the input table parses them (settings/settings.h).
  void read_settings(od::value& v, std::string_view object_name, settings& out);
  void read_setting(od::value& v, const setting& row, given& g);
  std::string_view number_token(od::value& v, const std::string& path, const char* must_be);

  const char* text_;
  size_t size_;
  bool release_;
  bool quiet_ = false;
  // Where a syntax error is looked for from (fail_syntax): the text's start,
  // or a sphere once text before it may have been handed back.
  const char* scan_from_ = nullptr;
  text_gap gap_;
  od::document& doc_;
  const char* released_to_;          // text before this was handed back (release_text_before)
  size_t released_lines_ = 0;        // newlines before released_to_
  const char* released_line_start_;  // just after the last of them
  // where()'s count so far: the line at counted_, and where that line starts.
  mutable const char* counted_ = text_;
  mutable size_t line_ = 1;
  mutable const char* line_start_ = text_;
};

// The number as written, for the input table's parsers.
std::string_view reader::number_token(od::value& v, const std::string& path, const char* must_be) {
  const char* start = at(v);
  od::json_type t;
  if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
  if (t != od::json_type::number) fail(path, must_be, start);
  std::string_view token = v.raw_json_token();
  while (!token.empty() && std::string_view(" \t\r\n").find(token.back()) != std::string_view::npos)
    token.remove_suffix(1);
  if (!json_number(token)) fail(path, quote_token(token) + " is not a JSON number", start);
  return token;
}

void reader::read_setting(od::value& v, const setting& row, given& g) {
  const std::string path(row.file_key);
  const char* start = at(v);
  g.source = path;
  g.where = where(start);
  const auto parse = [&](std::string_view text, const std::string& blame) {
    if (auto e = parse_value(row, text, g.v, g.tokens)) fail(blame, *e, start);
  };
  switch (row.type) {
    case value_type::integer: parse(number_token(v, path, "must be an integer"), path); break;
    case value_type::real: parse(number_token(v, path, "must be a number"), path); break;
    case value_type::aspect: {
      // A number, or a string the command line would take: "16:9", "1.5".
      od::json_type t;
      if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
      if (t == od::json_type::number) return parse(number_token(v, path, ""), path);
      if (t != od::json_type::string) fail(path, "must be a number or a string \"W:H\"", start);
      std::string_view text;
      if (error_code e = v.get_string().get(text)) fail_json(e, start);
      return parse(text, path);
    }
    case value_type::triple: {
      od::array arr = array(v, [&] { return path; }, "must be an array of 3 numbers");
      int n = 0;
      for (auto result : arr) {
        od::value el;
        if (error_code e = std::move(result).get(el)) fail_json(e, here());
        if (n == 3) fail(path, "must be an array of 3 numbers", starts_value(*at(el)) ? start : at(el));
        const std::string el_path = path + "[" + std::to_string(n) + "]";
        const std::string_view token = number_token(el, el_path, "must be a number");
        if (auto e = parse_real(token, g.v.triple[n])) fail(el_path, *e, at(el));
        g.tokens[size_t(n)] = token.substr(0, 64);
        ++n;
      }
      if (n != 3) fail(path, "must be an array of 3 numbers", start);
      break;
    }
    case value_type::name: {  // a string the command line would take: "orthographic"
      od::json_type t;
      if (v.type().get(t) != simdjson::SUCCESS) fail_json("not a JSON value", start);
      if (t != od::json_type::string) fail(path, "must be a string", start);
      std::string_view text;
      if (error_code e = v.get_string().get(text)) fail_json(e, start);
      g.tokens[0] = std::string(text.substr(0, 64));
      return parse(text, path);
    }
    case value_type::flag: {  // true or false: "shadows": true
      bool b = false;
      if (v.get_bool().get(b) != simdjson::SUCCESS) fail(path, "must be true or false", start);
      g.v.flag = b;
      g.tokens[0] = b ? "true" : "false";
      break;
    }
    default: fail(path, "is not a scene file key", start);
  }
}

// The keys of "camera", "sky", "light" or "ambient_occlusion": the input
// table's rows with that file key prefix.
void reader::read_settings(od::value& v, std::string_view object_name, settings& out) {
  static const auto known_of = [](std::string_view prefix) {
    std::vector<std::string_view> names;
    for (const setting& row : input_table())
      if (is_scene_row(row) && row.file_key.substr(0, row.file_key.find('.')) == prefix) names.push_back(row.file_key.substr(prefix.size() + 1));
    return names;
  };
  static const std::vector<std::string_view> camera_keys = known_of("camera"), sky_keys = known_of("sky"),
                                             light_keys = known_of("light"), ao_keys = known_of("ambient_occlusion");
  const std::vector<std::string_view>& known = object_name == "camera" ? camera_keys
                                               : object_name == "sky"  ? sky_keys
                                               : object_name == "light" ? light_keys
                                                                        : ao_keys;
  const auto object_path = [&] { return std::string(object_name); };
  fields(object(v, object_path), object_path, known, [&](int key, od::value& value) {
    const setting& row = *find_file_key(std::string(object_name) + "." + std::string(known[size_t(key)]));
    given g;
    read_setting(value, row, g);
    out[row.id] = std::move(g);
  });
}

void reader::read_spheres(od::value& v, std::vector<sphere>& out) {
  const char* start = at(v);
  od::array list = array(v, [] { return std::string("spheres"); }, "must be an array");
  // Exactly the spheres there are (a pass over the index, not the text). A
  // malformed array fails the count, which leaves the iterator lost (at the
  // end of the text): the error is reported from the text.
  size_t count = 0;
  if (error_code e = list.count_elements().get(count)) fail_json(e, start);
  out.reserve(count);
  advise_huge_pages(out.data(), out.capacity() * sizeof(sphere));
  size_t k = 0;
  for (auto result : list) {
    if (error_code e = result.error()) fail_json(e, here());
    od::value& item = result.value_unsafe();  // in place, as in fields()
    const char* sphere_at = at(item);
    out.push_back(read_sphere(item, k));
    if (++k % 4096 == 0) {
      release_text_before(sphere_at);
      scan_from_ = sphere_at;  // kept, and all before it read
    }
  }
}

sphere reader::read_sphere(od::value& item, size_t k) {
  const auto at_k = [&k] { return "spheres[" + std::to_string(k) + "]"; };
  const char* sphere_at = at(item);
  // Where each value is (nullptr: not given), for the errors about it.
  const char *center_at = nullptr, *radius_at = nullptr, *color_at = nullptr;
  sphere ball;
  static constexpr std::string_view sphere_keys[] = {"center", "radius", "shade", "color"};
  fields(object(item, at_k), at_k, sphere_keys, [&](int key, od::value& value) {
    switch (key) {
      case 0:
        center_at = at(value);
        ball.center = triple(value, [&] { return at_k() + ".center"; });
        break;
      case 1:
        radius_at = at(value);
        ball.radius = number(value, [&] { return at_k() + ".radius"; });
        break;
      case 2: {
        const char* shade_at = at(value);
        // The names as usually written, compared in place (a closing quote
        // cannot come early: it would be escaped); others are unescaped first.
        const std::string_view raw = value.raw_json_token();
        if (raw.rfind("\"normal\"", 0) == 0 || raw.rfind("\"flat\"", 0) == 0 || raw.rfind("\"lit\"", 0) == 0) {
          ball.shade = raw[1] == 'f' ? shading::flat : raw[1] == 'l' ? shading::lit : shading::normal;
          break;
        }
        std::string_view s;
        const error_code e = value.get_string().get(s);
        if (e != simdjson::SUCCESS && e != simdjson::INCORRECT_TYPE) fail_json(e, shade_at);
        if (e != simdjson::SUCCESS || (s != "normal" && s != "flat" && s != "lit"))
          fail(at_k() + ".shade", "must be \"normal\", \"flat\" or \"lit\"", shade_at);
        ball.shade = s == "flat" ? shading::flat : s == "lit" ? shading::lit : shading::normal;
        break;
      }
      case 3:
        color_at = at(value);
        ball.color = triple(value, [&] { return at_k() + ".color"; });
        break;
    }
  });
  if (!center_at) fail(at_k() + ".center", "is required", sphere_at);
  if (!radius_at) fail(at_k() + ".radius", "is required", sphere_at);
  if (ball.shade != shading::normal && !color_at)
    fail(at_k() + ".color", ball.shade == shading::flat ? "is required for flat shading" : "is required for lit shading",
         sphere_at);
  if (auto e = validate(ball, k)) {
    const char* blame = e->field == scene_field::sphere_center   ? center_at
                        : e->field == scene_field::sphere_radius ? radius_at
                                                                 : color_at;
    fail(path(*e), e->message, blame);
  }
  return ball;
}

const char* reader::read_window(std::vector<sphere>& out, size_t& k) {
  const char* after = nullptr;
  od::array list;
  if (doc_.get_array().get(list) != simdjson::SUCCESS) return after;
  try {
    for (auto result : list) {
      if (result.error() != simdjson::SUCCESS) break;
      od::value& item = result.value_unsafe();  // in place, as in fields()
      const sphere b = read_sphere(item, k);
      const char* next = here();
      if (!next) break;
      out.push_back(b);
      ++k;
      after = next;
    }
  } catch (const window_failed&) {
  }
  return after;
}

scene_file_contents reader::read() {
  scene_file_contents p;
  od::object root;
  if (error_code e = doc_.get_object().get(root)) {
    if (e == simdjson::INCORRECT_TYPE) fail("", "must be an object", here());
    fail_json(e, here());
  }
  static constexpr std::string_view root_keys[] = {"camera", "sky", "spheres", "light", "ambient_occlusion"};
  fields(root, [] { return std::string(); }, root_keys, [&](int key, od::value& value) {
    if (key == 2) read_spheres(value, p.scene.spheres);
    else read_settings(value, root_keys[key], p.keys);
  });
  // At the end, the document has no current location.
  const char* rest = nullptr;
  if (doc_.current_location().get(rest) == simdjson::SUCCESS) fail_json(simdjson::TRAILING_CONTENT, rest);
  // One file gives vfov or viewport_height, not both.
  if (auto e = check_groups(p.keys)) throw failure{{e->source, e->message}};
  return p;
}

std::variant<scene_file_contents, scene_file_error> parse_padded(const padded_text& t) {
  od::parser parser(max_scene_file_bytes);
  if (error_code e = parser.allocate(std::max<size_t>(t.size(), 1), max_depth))
    return scene_file_error{"", (e == simdjson::MEMALLOC ? "out of memory indexing " + bytes_text(t.size())
                                                         : "cannot index: " + json_error(e))};
  od::document doc;
  // Stage one (the index of the whole text) says nothing of where; a string
  // not closed or over a line's end (a quote missing, or one too many) is
  // placed by the scan.
  const error_code indexed = parser.iterate(t.data(), t.size(), t.capacity()).get(doc);
  if (indexed && indexed != simdjson::UNCLOSED_STRING && indexed != simdjson::UNESCAPED_CHARS)
    return scene_file_error{"", "not valid JSON: " + json_error(indexed)};
  try {
    reader r(t.data(), t.size(), t.mapped(), doc);
    if (indexed) r.fail_index(indexed);
    return r.read();
  } catch (const failure& x) {
    return x.e;
  } catch (const std::bad_alloc&) {
    return scene_file_error{"", "out of memory"};
  }
}

// A large text is parsed without an index of all of it: simdjson's index
// holds 4 bytes for each of its ~20 structural characters a sphere, which
// for a million spheres is 80 MB of fresh memory, slower to fault in on some
// virtual machines than the parse itself. Instead the spheres array is read
// a window at a time: each run of whole spheres (up to the window's last
// '}') is indexed and parsed as an array of its own ("[" + run + "]") with the
// same code as the whole text's, into one reused buffer and index. The rest
// of the text, with the array's contents left out, is then parsed as a
// skeleton by the whole-text reader, whose places after the array are
// reported as in the whole text (text_gap).
//
// Any doubt ends it: a sphere or window that does not parse, a separator
// other than one comma, a skeleton error, a text that changed while read.
// The whole text is then parsed the usual way, which gives the same result
// or the error with its place. So the windows only ever have to get right
// what parses; they never report.

// Where a window's bytes come from: copied out of a text in memory, or read
// from a file at an offset. False when fewer than n bytes were there.
using text_source = std::function<bool(size_t offset, size_t n, char* to)>;

// Texts from windowed_from bytes on are read a window of default_window
// bytes at a time (scene_file.h).
constexpr size_t default_window = size_t(512) << 10;

// How far into the text the "spheres" key is looked for.
constexpr size_t skim_bytes = size_t(64) << 10;

// The offset of the '[' of the root object's "spheres" array, found in the
// text's first bytes by a skim that follows strings and nesting, or nullopt.
std::optional<size_t> spheres_array_at(std::string_view t) {
  size_t i = 0, depth = 0;
  while (i < t.size() && json_space(t[i])) ++i;
  if (i == t.size() || t[i] != '{') return std::nullopt;
  for (; i < t.size(); ++i) {
    const char c = t[i];
    if (c == '{' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ']') {
      if (depth-- == 1) return std::nullopt;  // the root ended
    } else if (c == '"') {
      const size_t from = ++i;
      for (; i < t.size() && t[i] != '"'; ++i)
        if (t[i] == '\\') ++i;
      if (i >= t.size()) return std::nullopt;
      if (depth != 1 || t.substr(from, i - from) != "spheres") continue;
      size_t j = i + 1;
      while (j < t.size() && json_space(t[j])) ++j;
      if (j == t.size() || t[j] != ':') continue;  // a value, not the key
      ++j;
      while (j < t.size() && json_space(t[j])) ++j;
      if (j == t.size() || t[j] != '[') return std::nullopt;
      return j;
    }
  }
  return std::nullopt;
}

// Between the spheres of the array: whitespace, then one comma after a
// sphere, then the ']'. Skips them from s (expect says what came last) up to
// the next other byte, or end.
enum class separator { first, after_sphere, after_comma };
const char* skip_separators(const char* s, const char* end, separator& expect) {
  for (;;) {
    while (s < end && json_space(*s)) ++s;
    if (s == end || expect != separator::after_sphere || *s != ',') return s;
    expect = separator::after_comma;
    ++s;
  }
}

// The run of whole spheres from s to the '}' at last, parsed as an array of
// its own into spheres (k counts them): where the reader stopped, or null.
// The bytes before s and after last are the window buffer's own (a byte
// already passed, or buf[0]; the padding).
const char* read_run(od::parser& parser, const char* s, const char* last, std::vector<sphere>& spheres, size_t& k) {
  constexpr size_t pad = simdjson::SIMDJSON_PADDING;
  char* const doc_begin = const_cast<char*>(s) - 1;
  *doc_begin = '[';
  char* const doc_end = const_cast<char*>(last) + 2;
  doc_end[-1] = ']';
  std::memset(doc_end, 0, pad);
  od::document doc;
  const size_t len = size_t(doc_end - doc_begin);
  if (parser.iterate(doc_begin, len, len + pad).get(doc) != simdjson::SUCCESS) return nullptr;
  reader r(doc_begin, len, false, doc);
  r.window();
  return r.read_window(spheres, k);
}

// The skeleton: the text with the spheres array's contents [kept, close)
// left out, read as a whole text (its places reported as the whole file's,
// through gap), with the spheres the windows read.
std::optional<scene_file_contents> read_skeleton(const text_source& source, size_t size, const std::string& head,
                                                 size_t kept, size_t close, text_gap gap, od::parser& parser,
                                                 std::vector<sphere>&& spheres) {
  auto skeleton = padded_text::allocate(kept + (size - close));
  if (!skeleton) return std::nullopt;
  std::memcpy(skeleton->data(), head.data(), kept);
  if (!source(close, size - close, skeleton->data() + kept)) return std::nullopt;
  skeleton->finish(kept + (size - close));
  gap.at = skeleton->data() + kept;
  gap.head = std::string_view(head).substr(kept, quote_span);  // head holds skim_bytes or the whole text
  od::document doc;
  if (parser.iterate(skeleton->data(), skeleton->size(), skeleton->capacity()).get(doc) != simdjson::SUCCESS)
    return std::nullopt;
  try {
    reader r(skeleton->data(), skeleton->size(), false, doc);
    r.skeleton_of(gap);
    scene_file_contents c = r.read();
    if (!c.scene.spheres.empty()) return std::nullopt;
    c.scene.spheres = std::move(spheres);
    return c;
  } catch (const failure&) {
    return std::nullopt;
  }
}

// The scene of a text of `size` bytes read from `source` a window of about
// `window` bytes at a time, or nullopt (the caller parses the whole text).
std::optional<scene_file_contents> read_windowed(const text_source& source, size_t size, size_t window) try {
  constexpr size_t pad = simdjson::SIMDJSON_PADDING;
  std::string head(std::min(size, skim_bytes), '\0');
  if (!source(0, head.size(), head.data())) return std::nullopt;
  // (Not in the last quote_span bytes of a cut head: gap.head comes from it.)
  const std::optional<size_t> open =
      spheres_array_at(std::string_view(head).substr(0, head.size() == size ? size : head.size() - quote_span));
  if (!open) return std::nullopt;

  std::vector<sphere> spheres;
  // Room for as many as the rest could hold; pages no sphere fills are never touched.
  constexpr size_t min_sphere_bytes = sizeof(R"({"center":[0,0,0],"radius":1},)") - 1;
  spheres.reserve((size - *open) / min_sphere_bytes + 1);
  advise_huge_pages(spheres.data(), spheres.capacity() * sizeof(sphere));
  od::parser parser(max_scene_file_bytes);
  std::vector<char> buf;
  text_gap gap;
  size_t pos = *open + 1, k = 0, w = window, close = 0;
  separator expect = separator::first;
  for (;;) {
    const size_t n = std::min(w, size - pos);
    if (n == 0) return std::nullopt;  // the array never closes
    buf.resize(n + 2 + pad);
    char* const text = buf.data() + 1;  // text[i] is the whole text's pos + i
    if (!source(pos, n, text)) return std::nullopt;
    const char* const end = text + n;
    const char* s = skip_separators(text, end, expect);
    gap.pass(text, s);
    if (s == end) {  // all separators: on to the next window
      pos += n;
      continue;
    }
    if (*s == ']') {
      if (expect == separator::after_comma) return std::nullopt;  // a trailing comma
      close = pos + size_t(s - text);
      break;
    }
    if (expect == separator::after_sphere) return std::nullopt;  // no comma between spheres
    // The run of whole spheres: up to the window's last '}'.
    const char* last = static_cast<const char*>(memrchr(s, '}', size_t(end - s)));
    const bool at_end = pos + n == size;
    const char* after = nullptr;
    if (last) {
      after = read_run(parser, s, last, spheres, k);
      if (after && (after < s || after > last + 1)) return std::nullopt;
    }
    if (!after) {
      // A run that did not give one whole sphere: in a scene every '}' ends a
      // sphere or an object of the skeleton, so its first sphere is bad.
      if (last || at_end) return std::nullopt;
      // No '}' at all: a sphere longer than the window.
      pos += size_t(s - text);
      w *= 2;
      continue;
    }
    w = window;
    expect = separator::after_sphere;
    if (*after == ']' && after != last + 1) {  // the array's own ']'
      gap.pass(s, after);
      close = pos + size_t(after - text);
      break;
    }
    if (*after != ']' && *after != ',') return std::nullopt;
    // On from the ',' after the last sphere read, or from just after the run.
    const char* next = *after == ',' ? after : last + 1;
    gap.pass(s, next);
    pos += size_t(next - text);
  }

  return read_skeleton(source, size, head, *open + 1, close, gap, parser, std::move(spheres));
} catch (const std::bad_alloc&) {
  return std::nullopt;
}



}  // namespace

std::optional<scene_file_contents> read_scene_windows(std::string_view text, size_t window) {
  const auto copy = [&](size_t offset, size_t n, char* to) {
    std::memcpy(to, text.data() + offset, n);
    return true;
  };
  return read_windowed(copy, text.size(), std::max<size_t>(window, 1));
}

std::variant<scene_file_contents, scene_file_error> read_scene_text(std::string_view text) {
  if (text.size() > max_scene_file_bytes) return too_large(text.size());
  if (text.size() >= windowed_from)
    if (auto c = read_scene_windows(text, default_window)) return std::move(*c);
  auto t = padded_text::allocate(text.size());
  if (!t) return scene_file_error{"", "out of memory copying " + bytes_text(text.size())};
  std::memcpy(t->data(), text.data(), text.size());
  t->finish(text.size());
  return parse_padded(*t);
}

std::variant<scene_file_contents, scene_file_error> read_scene_file(const std::string& path) {
  const auto error = [](std::string why) { return scene_file_error{"", std::move(why), true}; };
  auto opened = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&opened)) return error(*why);
  regular_file& f = *std::get<std::unique_ptr<regular_file>>(opened);
  if (f.size() > max_scene_file_bytes) return too_large(f.size());
  const size_t size = size_t(f.size());
  if (size >= windowed_from) {
    // Read at offsets, a window at a time; a file that changes length meanwhile
    // is left to the whole read below, which reports it.
    const auto at = [&](size_t offset, size_t n, char* to) { return f.read_at(offset, n, to) == ptrdiff_t(n); };
    if (auto c = read_windowed(at, size, default_window))
      if (f.unchanged()) return std::move(*c);
  }
  // Room for the size fstat gave and one byte more: a file that grows while
  // read is refused at that byte, so memory never exceeds what was checked.
  auto t = padded_text::allocate(size);
  if (!t) return error("out of memory reading " + bytes_text(size));
  const ptrdiff_t got = f.read_at(0, size + 1, t->data());
  if (got < 0) return error(std::strerror(errno));
  if (size_t(got) > size) return error("grew while being read (was " + bytes_text(size) + ")");
  f.close();
  t->finish(size_t(got));
  return parse_padded(*t);
}

namespace {

// The file's camera and sky keys applied to the lesson's, as nothing overrides them.
std::variant<api::scene, scene_file_error> resolved(std::variant<scene_file_contents, scene_file_error>&& r) {
  if (auto* e = std::get_if<scene_file_error>(&r)) return std::move(*e);
  scene_file_contents& c = std::get<scene_file_contents>(r);
  if (auto e = resolve_scene(c.keys, c.scene)) return scene_file_error{e->source, e->message};
  return std::move(c.scene);
}

}  // namespace

std::variant<api::scene, scene_file_error> parse_scene_file(std::string_view text) {
  return resolved(read_scene_text(text));
}

std::variant<api::scene, scene_file_error> load_scene_file(const std::string& path) {
  return resolved(read_scene_file(path));
}

}  // namespace raycast
