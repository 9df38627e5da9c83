#include "particles/colormap.h"

#include <algorithm>
#include <cmath>

namespace raycast {
namespace {

#include "particles/colormap_data.inc"

// gray: entry k is k / 255 in every channel.
std::array<float, 3> gray_entry(int k) {
  const float g = float(k) / 255.0f;
  return {g, g, g};
}

}  // namespace

std::array<float, 3> colormap_color(colormap m, double v, double lo, double hi) {
  int k = 128;
  if (lo < hi) {
    // Halved, so that neither difference overflows (lo, hi and v may span
    // the doubles); NaN (none reaches here) would take the low end.
    const double t = (v / 2 - lo / 2) / (hi / 2 - lo / 2);
    k = t > 0.0 ? int(std::min(255.0, std::floor(std::min(t, 1.0) * 256.0))) : 0;
  }
  static constexpr const float (*tables[])[3] = {viridis_table, magma_table,   plasma_table,
                                                 inferno_table, cividis_table, coolwarm_table};
  if (m == colormap::gray) return gray_entry(k);
  const float* e = tables[size_t(m)][k];
  return {e[0], e[1], e[2]};
}

colormap colormap_named(std::string_view name) {
  for (size_t k = 0; k < std::size(colormap_names); ++k)
    if (colormap_names[k] == name) return colormap(k);
  return colormap::viridis;
}

}  // namespace raycast
