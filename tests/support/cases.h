// Scenes and backend modes shared by tests/ and bench/: one spelling of each.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "render/backend.h"
#include "scene/scene.h"

namespace raycast_test {

// A scene with a name: the stiff cases, the equivalence cameras.
struct scene_case {
  std::string name;
  raycast::api::camera cam;
  raycast::sky sky;
};

// The lesson's camera at w x h pixels.
raycast::api::camera sized(int64_t w, int64_t h);

inline raycast::scene make_scene(const raycast::api::camera& p = {}, const raycast::sky& s = {},
                                 std::vector<raycast::sphere> spheres = {}) {
  return raycast::make_scene(raycast::api::scene{p, {s.bottom, s.top}, std::move(spheres), std::nullopt, {}});
}

// S = max(1, |bottom|, |top|) over all channels: the scale of the error bounds
// (error_bounds.h).
double colour_scale(const raycast::sky& s);

// A backend at a precision; the reference has only exact.
struct mode {
  raycast::backend which;
  raycast::precision prec;
};
// Every mode, in all_backends order, exact before fast.
std::vector<mode> all_modes();
std::string name_of(const mode& m);  // "avx2_fast": a test-name suffix
inline void PrintTo(const mode& m, std::ostream* os) { *os << name_of(m); }

}  // namespace raycast_test
