#include "particles/elements.h"

#include <algorithm>
#include <cctype>

namespace raycast {
namespace {

struct element_row {
  std::string_view symbol;
  float radius;
  std::array<float, 3> color;
};

#include "particles/elements_data.inc"

// Tableau's ten colours as matplotlib's tab10 lists them: #1f77b4, #ff7f0e, ...
constexpr unsigned tab10[] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd,
                              0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22, 0x17becf};

bool same_symbol(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

const element_style* element_named(std::string_view name) {
  static const auto styles = [] {
    std::array<element_style, std::size(element_rows)> s{};
    for (size_t k = 0; k < s.size(); ++k) {
      const element_row& r = element_rows[k];
      const bool colored = r.color != std::array<float, 3>{0.0f, 0.0f, 0.0f};
      s[k] = {r.symbol, r.radius > 0.0f ? r.radius : default_element_radius, colored ? r.color : default_type_color};
    }
    return s;
  }();
  for (const element_style& e : styles)
    if (same_symbol(e.symbol, name)) return &e;
  return nullptr;
}

std::string_view element_symbol(int z) {
  return z >= 1 && size_t(z) <= std::size(element_rows) ? element_rows[z - 1].symbol : std::string_view();
}

std::array<float, 3> palette_color(size_t k) {
  const unsigned c = tab10[k % std::size(tab10)];
  return {float((c >> 16) & 0xff) / 255.0f, float((c >> 8) & 0xff) / 255.0f, float(c & 0xff) / 255.0f};
}

}  // namespace raycast
