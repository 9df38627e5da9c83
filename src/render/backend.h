// The ways to render: their names, whether this CPU runs them, and which
// kernel each one calls. The one place that maps backends to instruction sets.
#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <span>
#include <string_view>

#include "kernels/kernel.h"
#include "kernels/precision.h"
#include "simd/targets.h"

namespace raycast {

// The double reference, and one backend per target of simd/targets.h (the
// 1-lane scalar target, then the vector ones), each named as its target.
enum class backend : uint8_t {
  automatic,  // the best one this CPU runs
  reference,  // double, the oracle (reference/reference.h)
#define RAYCAST_BACKEND(name, arch, lanes, needs, flags) name,
  RAYCAST_TARGETS(RAYCAST_BACKEND)
#undef RAYCAST_BACKEND
};

// Every backend: the reference, then the targets in targets.h's order. A
// build has the targets of its own architecture only; backend_unavailable
// says why not.
inline constexpr backend all_backends[] = {
    backend::reference,
#define RAYCAST_BACKEND(name, arch, lanes, needs, flags) backend::name,
    RAYCAST_TARGETS(RAYCAST_BACKEND)
#undef RAYCAST_BACKEND
};
// The targets' backends (every one but the reference), and the vector ones:
// every target but the 1-lane one (targets.h lists it first), each tested
// against it (or skipped with the reason where this machine cannot run it).
static_assert(all_backends[1] == backend::scalar);
inline constexpr std::span<const backend> target_backends{all_backends + 1, std::size(all_backends) - 1};
inline constexpr std::span<const backend> simd_backends = target_backends.subspan(1);

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

// The kernels behind a backend: the sky kernel and the one for scenes with
// spheres (kernels/kernel.h); null for the reference (and for another
// architecture's targets).
struct target_kernels {
  kernels::sky_rows_fn sky = nullptr;
  kernels::sphere_rows_fn spheres = nullptr;
};
target_kernels kernels_for(backend b);

// What the 1-lane target's ray through pixel (i, j) hits (kernels/scalar.h's scalar_hit).
scalar_hit scalar_trace(const float_scene& f, int64_t i, int64_t j);

}  // namespace raycast
