// The ways to render: their names, whether this CPU runs them, and which
// kernel each one calls. The one place that maps backends to instruction sets.
#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "kernels/kernel.h"
#include "kernels/precision.h"

namespace raycast {

enum class backend : uint8_t {
  automatic,  // the best one this CPU runs
  reference,  // double, the oracle (reference/reference.h)
  scalar,     // float, one pixel at a time (kernels/scalar.h)
  sse2,       // 8 pixels a batch as two 4-lane halves; any x86-64
  avx2,       // 8 pixels a batch; AVX2 + FMA
  avx512,     // 16 pixels a batch; AVX-512 F + BW + VL
  neon,       // 8 pixels a batch as two 4-lane halves; any AArch64
};

// Every backend, x86's best last, then AArch64's. A build has the SIMD
// backends of its own architecture only; backend_unavailable says why not.
inline constexpr backend all_backends[] = {backend::reference, backend::scalar, backend::sse2,
                                           backend::avx2, backend::avx512, backend::neon};
// The vector backends, each tested against the scalar renderer (or skipped
// with the reason where this machine cannot run it).
inline constexpr backend simd_backends[] = {backend::sse2, backend::avx2, backend::avx512,
                                            backend::neon};

std::string_view to_string(backend b);
std::string_view to_string(precision p);
std::optional<backend> parse_backend(std::string_view name);
std::optional<precision> parse_precision(std::string_view name);

// The precision used when none is asked for.
inline constexpr precision default_precision = precision::exact;

// Why this machine cannot run the backend, or nullopt when it can.
std::optional<std::string> backend_unavailable(backend b);
// What `automatic` resolves to on this machine.
backend best_backend();

struct unsupported_backend : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The SIMD kernel behind a backend; null for reference and scalar, which
// render a pixel at a time without one (and for another architecture's).
kernels::sky_rows_fn sky_kernel_for(backend b);
// The same for scenes with spheres (kernels/sphere_kernel.inl).
kernels::sphere_rows_fn sphere_kernel_for(backend b);

}  // namespace raycast
