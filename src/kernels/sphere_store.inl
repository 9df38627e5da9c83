// The sphere kernel's stores of a batch's colours, as 8-bit or float pixels.
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/sphere_hit.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// Stores n pixels of a batch at column i0; Reversed, all N in the opposite order.
template <bool Float, bool Reversed = false>
RAYCAST_INLINE void store_batch(unsigned char* out, int64_t i0, int n, const vfloat c[3]) {
  if constexpr (Float) {
    float* dst = reinterpret_cast<float*>(out) + 3 * i0;
    if constexpr (Reversed) {
      store_rgbf(dst, reverse(c[0]), reverse(c[1]), reverse(c[2]));
    } else if (n == N) {
      store_rgbf(dst, c[0], c[1], c[2]);
    } else {
      alignas(64) float tmp[3 * N];
      store_rgbf(tmp, c[0], c[1], c[2]);
      __builtin_memcpy(dst, tmp, sizeof(float) * 3 * size_t(n));
    }
  } else {
    const rgb8_pack p = pack_rgb8<Reversed>(to_int(clamp(c[0], 0.0f, 1.0f) * 255.999f),
                                            to_int(clamp(c[1], 0.0f, 1.0f) * 255.999f),
                                            to_int(clamp(c[2], 0.0f, 1.0f) * 255.999f));
    unsigned char* dst = out + 3 * i0;
    if (Reversed || n == N) {
      store(dst, p);
    } else {
#ifdef RAYCAST_HAS_MASKED_BYTE_STORE
      store_first(dst, p, n);
#else
      alignas(64) unsigned char tmp[3 * N];
      store(tmp, p);
      __builtin_memcpy(dst, tmp, 3 * size_t(n));
#endif
    }
  }
}

// Stores the lanes of a batch at column i0 inside the band's window [c0, c1); row is column c0.
template <bool Float>
RAYCAST_INLINE void store_window(unsigned char* row, int64_t i0, int64_t c0, int64_t c1, const vfloat c[3]) {
  const int64_t lo = i0 > c0 ? i0 : c0, hi = i0 + N < c1 ? i0 + N : c1;
  if (lo == i0) {
    store_batch<Float>(row, i0 - c0, int(hi - lo), c);
    return;
  }
  constexpr size_t bpp = Float ? 12 : 3;
  alignas(64) unsigned char tmp[bpp * N];
  store_batch<Float>(tmp, 0, N, c);
  __builtin_memcpy(row + bpp * size_t(lo - c0), tmp + bpp * size_t(lo - i0), bpp * size_t(hi - lo));
}

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
