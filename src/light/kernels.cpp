#include "light/kernels.h"

#include "simd/cpu.h"

namespace raycast {

const std::vector<int>& light_widths() {
  static const std::vector<int> widths = [] {
    std::vector<int> w{4};
#if defined(RAYCAST_LIGHT_W8)
    if (cpu().avx2) w.push_back(8);
#endif
#if defined(RAYCAST_LIGHT_W16)
    if (cpu().avx512) w.push_back(16);
#endif
    return w;
  }();
  return widths;
}

const light_kernels& light_kernels_for(int width) {
  static const light_kernels w4 = kernels_w4();
#if defined(RAYCAST_LIGHT_W8)
  static const light_kernels w8 = cpu().avx2 ? kernels_w8() : w4;
#else
  static const light_kernels& w8 = w4;
#endif
#if defined(RAYCAST_LIGHT_W16)
  static const light_kernels w16 = cpu().avx512 ? kernels_w16() : w8;
#else
  static const light_kernels& w16 = w8;
#endif
  if (width == 0) width = light_widths().back();
  return width >= 16 ? w16 : width >= 8 ? w8 : w4;
}

}  // namespace raycast
