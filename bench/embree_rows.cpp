#include "embree_rows.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <memory>
#include <ostream>
#include <string>
#include <tuple>

#include "embree_peer.h"
#include "errors.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

// Our fastest backend for spheres: the last core path in available_paths()'
// order (sse2, avx2, avx512), exact (fast renders spheres as exact does).
const path& best_path() {
  static const path p = [] {
    path best;
    for (const path& q : available_paths())
      if (!q.autovec && q.prec == precision::exact) best = q;
    return best;
  }();
  return p;
}

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
  for (auto _ : state) {
    peer.render(band, m);
    benchmark::ClobberMemory();
  }
  const error_stats& err = m == embree_peer::mode::packet16 ? e.packet16 : e.single;
  state.counters["max_abs_err"] = err.max_abs_err;
  state.counters["rms_err"] = err.rms_err();
  state.counters["max_lsb"] = err.max_lsb;
  state.counters["lsb_mismatch"] = err.lsb_mismatch();
}

std::optional<double> ns_per_px(const run_table& t, const std::string& row, int64_t w, int64_t h) {
  const auto s = t.seconds(row + "|");
  if (!s) return std::nullopt;
  return *s * 1e9 / (double(w) * double(h));
}

}  // namespace

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes) {
  for (std::string_view sv : builtin_scene_names()) {
    const std::string name(sv);
    if (builtin_spheres(name)->empty()) continue;
    for (const auto& [w, h] : sizes)
      for (auto m : {embree_peer::mode::packet16, embree_peer::mode::single})
        benchmark::RegisterBenchmark(scene_row_name(mode_name(m), "float", name, w, h, 1, "rgb8").c_str(),
                                     bench_embree, name, w, h, m)
            ->Unit(benchmark::kMicrosecond);
  }
}

void print_embree_summary(std::ostream& os, const run_table& table, int64_t w, int64_t h) {
  const path& best = best_path();
  const std::string ours_label = best.backend + "/" + std::string(to_string(best.prec));
  const std::string prec(to_string(best.prec));
  const auto ours = ns_per_px(table, scene_row_name(best.backend, prec, "world", w, h, 1, "rgb8"), w, h);
  const auto e16 = ns_per_px(table, scene_row_name("embree16", "float", "world", w, h, 1, "rgb8"), w, h);
  const auto e1 = ns_per_px(table, scene_row_name("embree1", "float", "world", w, h, 1, "rgb8"), w, h);
  const auto book = ns_per_px(table, scene_row_name("book", "exact", "world", w, h, 1, "rgb8"), w, h);
  char line[256];
  // Sections with no row measured (filtered out by --benchmark_filter) are left out.
  if (ours || e16 || e1 || book)
    os << "\nPeers on world, " << w << "x" << h << ", 1 thread, rgb8 (ns/px; x = peer / ours):\n";
  auto peer_line = [&](const char* label, std::optional<double> v) {
    if (!v) return;
    std::snprintf(line, sizeof line, "  %-26s %9.2f", label, *v);
    os << line;
    if (ours && *ours > 0) {
      std::snprintf(line, sizeof line, "   %7.1fx", *v / *ours);
      os << line;
    }
    os << "\n";
  };
  peer_line(ours_label.c_str(), ours);
  peer_line("embree16 (rtcIntersect16)", e16);
  peer_line("embree1 (rtcIntersect1)", e1);
  peer_line("book (double, virtual)", book);
}

}  // namespace raycast::bench
