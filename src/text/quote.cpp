#include "text/quote.h"

#include <charconv>

namespace raycast {

std::string control_escaped(std::string_view text) {
  static constexpr char hex[] = "0123456789abcdef";
  std::string r;
  r.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      r.push_back(ch);
      continue;
    }
    r += "\\x";
    r.push_back(hex[c >> 4]);
    r.push_back(hex[c & 15]);
  }
  return r;
}

std::string quote_token(std::string_view token) {
  constexpr size_t excerpt_bytes = 32;
  size_t n = token.size();
  if (n > excerpt_bytes) {
    n = excerpt_bytes;
    while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xc0) == 0x80) --n;  // not inside a UTF-8 sequence
  }
  std::string r;
  r.reserve(n + 5);
  r.push_back('\'');
  r.append(control_escaped(token.substr(0, n)));
  if (n < token.size()) r.append("\u2026");
  r.push_back('\'');
  return r;
}

std::string number_text(double x) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, p) : std::to_string(x);
}

}  // namespace raycast
