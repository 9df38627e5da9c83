#include "render/backend.h"

#include "simd/cpu.h"

namespace raycast {

std::string_view to_string(backend b) {
  switch (b) {
    case backend::automatic: return "auto";
    case backend::reference: return "reference";
#define RAYCAST_NAME(name, arch, lanes, needs, flags) \
  case backend::name: return #name;
      RAYCAST_TARGETS(RAYCAST_NAME)
#undef RAYCAST_NAME
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
  switch (b) {
#define RAYCAST_AVAILABLE(name, arch, lanes, needs, flags)                                   \
  case backend::name:                                                                        \
    RAYCAST_ON_##arch(if (!f.name) return std::string("this CPU (or OS) cannot run ") + needs; \
                      return std::nullopt;)                                                  \
    return std::string(#name " exists only in " RAYCAST_ARCH_NAME_##arch " builds");
    RAYCAST_TARGETS(RAYCAST_AVAILABLE)
#undef RAYCAST_AVAILABLE
    default: return std::nullopt;
  }
}

backend best_backend() {
  backend best = backend::scalar;  // targets.h: the last one this CPU runs
  for (backend b : simd_backends)
    if (!backend_unavailable(b)) best = b;
  return best;
}

target_kernels kernels_for(backend b) {
  switch (b) {
#define RAYCAST_KERNELS(name, arch, lanes, needs, flags) \
  case backend::name: RAYCAST_ON_##arch(return {kernels::name::render_sky_rows, kernels::name::render_sphere_rows};) return {};
    RAYCAST_TARGETS(RAYCAST_KERNELS)
#undef RAYCAST_KERNELS
    default: return {};
  }
}

scalar_hit scalar_trace(const float_scene& f, int64_t i, int64_t j) {
  kernel_spheres sp = arrays_of(f.spheres);
  sp.axes = f.axes;
  sp.track_index = true;
  return kernels::scalar::trace_pixel(f, sp, i, j);
}

}  // namespace raycast
