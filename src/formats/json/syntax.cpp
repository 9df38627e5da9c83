#include "formats/json/syntax.h"

#include <cctype>
#include <utility>

#include "settings/values.h"

namespace raycast::json_detail {
namespace {

constexpr size_t excerpt_bytes = 32;

}  // namespace

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

std::string json_error(simdjson::error_code e) {
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

bool starts_value(char c) {
  return std::string_view("{[\"-tfn").find(c) != std::string_view::npos || (c >= '0' && c <= '9');
}

namespace {

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

}  // namespace

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

}  // namespace raycast::json_detail
