#include "text/quote.h"

#include <charconv>

namespace raycast {

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
  r.append(token.data(), n);
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
