// Colormaps for --color-by: a scalar property of each particle, mapped over
// a range [lo, hi] to a colour, as matplotlib, OVITO and ParaView do.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>

namespace raycast {

enum class colormap : uint8_t { viridis, magma, plasma, inferno, cividis, coolwarm, gray };
inline constexpr std::string_view colormap_names[] = {"viridis", "magma",    "plasma", "inferno",
                                                      "cividis", "coolwarm", "gray"};  // enum colormap's order

// The colour of value v over [lo, hi] (lo < hi): t = (v - lo) / (hi - lo),
// clamped into [0, 1], picks entry min(255, floor(256 t)) of the map's 256
// (matplotlib's ListedColormap lookup, no interpolation). lo = hi: every
// value is the map's middle entry (128). NaN takes the low end.
std::array<float, 3> colormap_color(colormap m, double v, double lo, double hi);

// The map a name (colormap_names) gives; "" is the default, viridis. The
// input table checks names before they reach here: another name is viridis.
colormap colormap_named(std::string_view name);

}  // namespace raycast
