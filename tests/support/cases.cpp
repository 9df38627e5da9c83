#include "cases.h"

#include <algorithm>
#include <cmath>

namespace raycast_test {

raycast::api::camera sized(int64_t w, int64_t h) {
  raycast::api::camera p;
  p.width = w;
  p.height = h;
  return p;
}

double colour_scale(const raycast::sky& s) {
  double m = 1.0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(s.bottom[k]), std::abs(s.top[k])});
  return m;
}

std::vector<mode> all_modes() {
  std::vector<mode> v;
  for (raycast::backend b : raycast::all_backends)
    for (raycast::precision p : {raycast::precision::exact, raycast::precision::fast})
      if (b != raycast::backend::reference || p == raycast::precision::exact) v.push_back({b, p});
  return v;
}

std::string name_of(const mode& m) {
  return std::string(to_string(m.which)) + "_" + std::string(to_string(m.prec));
}

}  // namespace raycast_test
