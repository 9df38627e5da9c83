#include "render/backend.h"

#include "simd/cpu.h"

namespace raycast {

std::string_view to_string(backend b) {
  switch (b) {
    case backend::automatic: return "auto";
    case backend::reference: return "reference";
    case backend::scalar: return "scalar";
    case backend::sse2: return "sse2";
    case backend::avx2: return "avx2";
    case backend::avx512: return "avx512";
    case backend::neon: return "neon";
  }
  return "?";
}

std::string_view to_string(precision p) { return p == precision::exact ? "exact" : "fast"; }

std::optional<backend> parse_backend(std::string_view name) {
  if (name == to_string(backend::automatic)) return backend::automatic;
  for (backend b : all_backends)
    if (name == to_string(b)) return b;
  return std::nullopt;
}

std::optional<precision> parse_precision(std::string_view name) {
  for (precision p : {precision::exact, precision::fast})
    if (name == to_string(p)) return p;
  return std::nullopt;
}

std::optional<std::string> backend_unavailable(backend b) {
  const cpu_features& f = cpu();
#if RAYCAST_HAVE_X86_KERNELS
  switch (b) {
    case backend::sse2:
      if (!f.sse2) return std::string("this CPU cannot run SSE2");
      break;
    case backend::avx2:
      if (!f.avx2_fma) return std::string("this CPU (or OS) cannot run AVX2 + FMA");
      break;
    case backend::avx512:
      if (!f.avx512) return std::string("this CPU (or OS) cannot run AVX-512 F+BW+VL");
      break;
    default: break;
  }
#else
  if (b == backend::sse2 || b == backend::avx2 || b == backend::avx512)
    return std::string(to_string(b)) + " exists only in x86-64 builds";
#endif
#if RAYCAST_HAVE_NEON_KERNELS
  if (b == backend::neon && !f.neon) return std::string("this CPU cannot run NEON");
#else
  if (b == backend::neon) return std::string("neon exists only in AArch64 builds");
#endif
  (void)f;
  return std::nullopt;
}

backend best_backend() {
  for (backend b : {backend::avx512, backend::avx2, backend::sse2, backend::neon})
    if (!backend_unavailable(b)) return b;
  return backend::scalar;
}

kernels::sky_rows_fn sky_kernel_for(backend b) {
  switch (b) {
#if RAYCAST_HAVE_X86_KERNELS
    case backend::sse2: return kernels::sse2::render_sky_rows;
    case backend::avx2: return kernels::avx2::render_sky_rows;
    case backend::avx512: return kernels::avx512::render_sky_rows;
#endif
#if RAYCAST_HAVE_NEON_KERNELS
    case backend::neon: return kernels::neon::render_sky_rows;
#endif
    default: return nullptr;
  }
}

kernels::sphere_rows_fn sphere_kernel_for(backend b) {
  switch (b) {
#if RAYCAST_HAVE_X86_KERNELS
    case backend::sse2: return kernels::sse2::render_sphere_rows;
    case backend::avx2: return kernels::avx2::render_sphere_rows;
    case backend::avx512: return kernels::avx512::render_sphere_rows;
#endif
#if RAYCAST_HAVE_NEON_KERNELS
    case backend::neon: return kernels::neon::render_sphere_rows;
#endif
    default: return nullptr;
  }
}

}  // namespace raycast
