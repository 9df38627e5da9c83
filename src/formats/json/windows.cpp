#include <string.h>  // memrchr

#include "formats/json/reader.h"
#include "memory/pages.h"

namespace raycast::json_detail {
namespace {

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

}  // namespace

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



}  // namespace raycast::json_detail
