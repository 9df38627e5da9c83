#include "formats/ply/header.h"

#include <charconv>

#include "formats/ply.h"
#include "text/names.h"
#include "text/quote.h"

namespace raycast::ply_detail {

std::string shown(std::string_view text, size_t most) {
  if (text.size() <= most) return control_escaped(text);
  while (most > 0 && (static_cast<unsigned char>(text[most]) & 0xc0) == 0x80) --most;  // not inside a UTF-8 sequence
  return control_escaped(text.substr(0, most)) + "\u2026";
}
[[noreturn]] void fail(std::string path, std::string why, uint64_t offset) {
  throw ply_error{shown(path), shown(why, 512) + at_byte(offset)};
}

namespace {

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> w;
  size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t')) ++k;
    const size_t start = k;
    while (k < line.size() && line[k] != ' ' && line[k] != '\t') ++k;
    if (k > start) w.push_back(line.substr(start, k - start));
  }
  return w;
}

ply_type type_named(std::string_view word, const std::string& path, uint64_t at) {
  for (size_t k = 0; k < std::size(types); ++k)
    if (word == types[k].name || word == types[k].other_name) return ply_type(k);
  fail(path, not_one_of(word, quote_token(word), type_names, "") + ": not a PLY type", at);
}

uint64_t count_of(std::string_view word, const std::string& path, uint64_t at) {
  uint64_t n = 0;
  const auto [p, ec] = std::from_chars(word.data(), word.data() + word.size(), n);
  if (ec != std::errc() || p != word.data() + word.size())
    fail(path, quote_token(word) + " is not a count (a whole number from 0 to 2^64 - 1)", at);
  return n;
}

void add_property(header& h, const std::vector<std::string_view>& w, uint64_t at) {
  if (h.elements.empty()) fail("header", "a property before any element", at);
  element& e = h.elements.back();
  const bool list = w.size() > 1 && w[1] == "list";
  if (w.size() != (list ? 5u : 3u))
    fail("header", list ? "want 'property list COUNT_TYPE ITEM_TYPE NAME'" : "want 'property TYPE NAME'", at);
  property p;
  p.name = std::string(w.back());
  p.list = list;
  p.at = at;
  const std::string path = e.name + "." + p.name;
  if (!e.names.insert(p.name).second) fail(path, "is declared twice", at);
  if (list) p.count_type = type_named(w[2], path, at);
  p.type = type_named(w[list ? 3 : 1], path, at);
  if (list && is_real(p.count_type)) fail(path, "a list's count must be an integer type", at);
  p.offset = e.row_bytes;
  e.row_bytes += bytes_of(p.type);
  e.props.push_back(std::move(p));
}

// One header line (without its end of line) at byte `at`; false at end_header.
bool header_line(header& h, std::string_view line, uint64_t at, bool& have_format) {
  const std::vector<std::string_view> w = words_of(line);
  if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return true;
  if (w[0] == "end_header") {
    if (!have_format) fail("header", "no format line before end_header", at);
    return false;
  }
  if (w[0] == "format") {
    constexpr std::string_view formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    if (w.size() != 3 || w[2] != "1.0") fail("header", "want 'format ascii|binary_little_endian|binary_big_endian 1.0'", at);
    size_t k = 0;
    if (auto why = parse_name(w[1], formats, k)) fail("header", "format: " + *why, at);
    h.format = encoding(k);
    have_format = true;
  } else if (w[0] == "element") {
    if (w.size() != 3) fail("header", "want 'element NAME COUNT'", at);
    element e;
    e.name = std::string(w[1]);
    e.count = count_of(w[2], e.name, at);
    e.at = at;
    h.elements.push_back(std::move(e));
  } else if (w[0] == "property") {
    add_property(h, w, at);
  } else {
    fail("header", quote_token(line) + ": not a PLY header line (format, element, property, comment, end_header)", at);
  }
  return true;
}

}  // namespace

header parse_header(std::string_view text, uint64_t file_size) {
  const size_t first = text.find('\n');
  if (first == std::string_view::npos || (text.substr(0, first) != "ply" && text.substr(0, first) != "ply\r"))
    fail("", "is not a PLY file: it does not begin with a line 'ply'", 0);
  header h;
  bool have_format = false;
  for (size_t at = first + 1;;) {
    const size_t end = text.find('\n', at);
    if (end == std::string_view::npos) {
      if (text.size() == file_size) fail("header", "ends without end_header", file_size);
      fail("header", "has no end_header in its first " + std::to_string(max_ply_header_bytes) + " bytes", at);
    }
    std::string_view line = text.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!header_line(h, line, at, have_format)) {
      h.bytes = end + 1;
      return h;
    }
    at = end + 1;
  }
}

}  // namespace raycast::ply_detail
