// The scene file reader's parts (formats/json.h is its face): the padded
// text simdjson reads, the reader that streams a scene out of simdjson's
// On-Demand iterator into the description (no document tree), and the
// windowed read of a large text's spheres array (windows.cpp).
#pragma once
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <simdjson.h>

#include "formats/json.h"
#include "formats/json/syntax.h"
#include "memory/pages.h"
#include "text/names.h"

namespace raycast::json_detail {

namespace od = simdjson::ondemand;
using simdjson::error_code;

// simdjson's On-Demand parser indexes the input with 32-bit offsets.
static_assert(max_scene_file_bytes <= simdjson::SIMDJSON_MAXSIZE_BYTES);

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

inline std::string bytes_text(uint64_t n) { return std::to_string(n) + " bytes"; }

inline scene_file_error too_large(uint64_t n) {
  return {"", "is " + bytes_text(n) + "; a scene file may be at most 4 GiB - 1 (" + bytes_text(max_scene_file_bytes) + ")"};
}

// A short quote of the input at a place: the token there (a number, string or
// word), or the rest of the line from an object or array, cut at a character
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


// A whole padded text parsed: its scene, or why not.
std::variant<scene_file_contents, scene_file_error> parse_padded(const padded_text& t);

// Where a window's bytes come from: copied out of a text in memory, or read
// from a file at an offset. False when fewer than n bytes were there.
using text_source = std::function<bool(size_t offset, size_t n, char* to)>;

// Texts from windowed_from bytes on are read a window of default_window
// bytes at a time (formats/json.h).
constexpr size_t default_window = size_t(512) << 10;

// The scene of a text of `size` bytes read from `source` a window of about
// `window` bytes at a time, or nullopt (the caller parses the whole text).
std::optional<scene_file_contents> read_windowed(const text_source& source, size_t size, size_t window);

}  // namespace raycast::json_detail
