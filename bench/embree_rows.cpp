#include "embree_rows.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "embree_peer.h"
#include "errors.h"
#include "rows.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

const char* mode_name(embree_peer::mode m) {
  return m == embree_peer::mode::packet16 ? "embree16" : "embree1";
}

scene builtin_scene(const std::string& name, int64_t w, int64_t h) {
  return make_scene(sized(w, h), {}, *builtin_spheres(name));
}

// Embree's errors against the double reference, both modes, measured band by
// band (float colours and bytes), once per scene and size.
struct embree_errors {
  error_stats packet16, single;
  std::string failure;  // Embree's message when the device or scene failed
};

const embree_errors& errors_for(const std::string& name, int64_t w, int64_t h) {
  static std::map<std::tuple<std::string, int64_t, int64_t>, embree_errors> cache;
  const auto key = std::make_tuple(name, w, h);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const scene s = builtin_scene(name, w, h);
  const embree_peer peer(s);
  embree_errors e;
  e.failure = peer.error();
  if (e.failure.empty()) {
    constexpr int64_t rows = 16;
    std::vector<float> f32(size_t(w) * 3 * rows);
    std::vector<unsigned char> rgb8(size_t(w) * 3 * rows);
    for (int64_t r0 = 0; r0 < h; r0 += rows) {
      const int64_t r1 = std::min(h, r0 + rows);
      const raycast_test::reference_band ref(s, r0, r1);
      for (auto m : {embree_peer::mode::packet16, embree_peer::mode::single}) {
        peer.render(image_band{f32.data(), size_t(w) * 12, pixel_format::rgb_f32, r0, r1}, m);
        // The peer's bytes are these colours quantized (embree_peer's store):
        // one trace gives both outputs.
        for (size_t k = 0; k < size_t(r1 - r0) * size_t(w) * 3; ++k)
          rgb8[k] = static_cast<unsigned char>(int(std::clamp(f32[k], 0.0f, 1.0f) * 255.999f));
        ref.compare(f32.data(), rgb8.data(), m == embree_peer::mode::packet16 ? e.packet16 : e.single);
      }
    }
    if (e.failure.empty()) e.failure = peer.error();
  }
  return cache.emplace(key, std::move(e)).first->second;
}

void bench_embree(benchmark::State& state, std::string name, int64_t w, int64_t h, embree_peer::mode m) {
  const embree_errors& e = errors_for(name, w, h);
  if (!e.failure.empty()) {
    state.SkipWithError(e.failure.c_str());
    return;
  }
  const scene s = builtin_scene(name, w, h);
  const embree_peer peer(s);
  const size_t stride = size_t(w) * 3;
  const image_band band{scratch(stride * size_t(h)), stride, pixel_format::rgb8, 0, h};
  time_pixels(state, double(w * h), [&] { peer.render(band, m); });
  const error_stats& err = m == embree_peer::mode::packet16 ? e.packet16 : e.single;
  state.counters["max_abs_err"] = err.max_abs_err;
  state.counters["rms_err"] = err.rms_err();
  state.counters["max_lsb"] = err.max_lsb;
  state.counters["lsb_mismatch"] = err.lsb_mismatch();
}

}  // namespace

const path& best_sphere_path() {
  static const path p = [] {
    path best;
    for (const path& q : available_paths())
      if (!q.autovec && q.prec == precision::exact) best = q;
    return best;
  }();
  return p;
}

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes) {
  for (std::string_view sv : builtin_scene_names()) {
    const std::string name(sv);
    if (builtin_spheres(name)->empty()) continue;
    for (const auto& [w, h] : sizes)
      for (auto m : {embree_peer::mode::packet16, embree_peer::mode::single}) {
        const row_id r = render_row(mode_name(m), "float", name, w, h, 1, "rgb8");
        add_row(r.name, r.fields, benchmark::kMicrosecond, bench_embree, name, w, h, m);
      }
  }
}

}  // namespace raycast::bench
