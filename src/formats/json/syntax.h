// The JSON text itself, for the scene file reader's messages: a short quote
// of the input at a place, simdjson's errors in plain terms, and the first
// place where a text breaks JSON's grammar, found by a scan of its own
// (simdjson's iterator can stand far past a syntax error by then).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <simdjson.h>

namespace raycast::json_detail {

// A scene nests four levels deep ({"spheres": [{"center": [...]}]}). The
// reader refuses deeper input itself, at the first level the format does not
// have (a value of the wrong type), so nesting costs nothing however deep;
// simdjson is given a small bound as well (its On-Demand front end checks it
// only in development builds).
constexpr size_t max_depth = 32;

// A short quote of the input at a place: the token there (a number, string or
// word), or the rest of the line from an object or array, cut at a character
// boundary with "…" when longer than 32 bytes.
std::string excerpt(std::string_view rest);
// simdjson's error in plain terms.
std::string json_error(simdjson::error_code e);
inline bool json_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
// Whether text is a number as JSON writes it: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
bool json_number(std::string_view t);
// Whether c can start a JSON value.
bool starts_value(char c);

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
// The first syntax error from p on, where a value is expected inside the
// containers open (outermost first), or nullopt when the text to end is JSON.
std::optional<syntax_fault> first_syntax_error(const char* p, const char* end, std::vector<open_bracket> open);

}  // namespace raycast::json_detail
