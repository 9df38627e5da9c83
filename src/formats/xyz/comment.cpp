#include "formats/xyz/comment.h"

#include <algorithm>
#include <cctype>

#include "formats/input/fields.h"

namespace raycast::formats::xyz {
namespace {

bool token_end(char c) { return input::is_blank(c) || c == '='; }

// A quoted, bracketed or bare word at s[at]; false where a quote or bracket
// never closes.
bool word(std::string_view s, size_t& at, std::string& out) {
  out.clear();
  if (at < s.size() && s[at] == '"') {
    for (++at; at < s.size() && s[at] != '"'; ++at) {
      if (s[at] == '\\' && at + 1 < s.size()) ++at;
      out.push_back(s[at]);
    }
    if (at >= s.size()) return false;
    ++at;
    return true;
  }
  if (at < s.size() && (s[at] == '{' || s[at] == '[')) {
    const char close = s[at] == '{' ? '}' : ']';
    const size_t end = s.find(close, at);
    if (end == std::string_view::npos) return false;
    out.assign(s.substr(at + 1, end - at - 1));
    at = end + 1;
    return true;
  }
  while (at < s.size() && !token_end(s[at])) out.push_back(s[at++]);
  return true;
}

bool same_key(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::optional<key_values> parse_key_values(std::string_view s) {
  key_values kv;
  size_t at = 0;
  std::string key, value;
  for (;;) {
    while (at < s.size() && input::is_blank(s[at])) ++at;
    if (at == s.size()) return kv;
    if (!word(s, at, key) || key.empty()) return std::nullopt;
    while (at < s.size() && input::is_blank(s[at])) ++at;
    if (at < s.size() && s[at] == '=') {
      ++at;
      while (at < s.size() && input::is_blank(s[at])) ++at;
      if (!word(s, at, value)) return std::nullopt;
      kv.emplace_back(key, value);
    } else {
      kv.emplace_back(key, "T");
    }
    if (at < s.size() && !input::is_blank(s[at])) return std::nullopt;
  }
}

specs_result parse_properties(std::string_view v) {
  specs_result r;
  std::vector<std::string_view> parts;
  for (size_t at = 0;;) {
    const size_t colon = v.find(':', at);
    parts.push_back(v.substr(at, colon == std::string_view::npos ? std::string_view::npos : colon - at));
    if (colon == std::string_view::npos) break;
    at = colon + 1;
  }
  if (parts.size() % 3 != 0) {
    r.error = "Properties is not NAME:TYPE:COUNT triples";
    return r;
  }
  for (size_t j = 0; j < parts.size(); j += 3) {
    const auto count = input::parse_int<uint32_t>(parts[j + 2]);
    const std::string_view type = parts[j + 1];
    if (parts[j].empty() || type.size() != 1 || std::string_view("SRIL").find(type[0]) == std::string_view::npos ||
        !count || *count < 1 || *count > 64) {
      r.error = "Properties has a bad entry " +
                input::quoted(std::string(parts[j]) + ":" + std::string(type) + ":" + std::string(parts[j + 2]));
      return r;
    }
    for (const property_spec& p : r.specs)
      if (p.name == parts[j]) {
        r.error = "Properties names " + std::string(parts[j]) + " twice";
        return r;
      }
    r.specs.push_back({std::string(parts[j]), type[0], *count});
  }
  return r;
}

const std::string* find_key(const key_values& kv, std::string_view key) {
  for (const auto& [k, v] : kv)
    if (same_key(k, key)) return &v;
  return nullptr;
}

}  // namespace raycast::formats::xyz
