#include "embree_rows.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <tuple>

#include "embree_peer.h"
#include "errors.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

constexpr int full_counts[] = {1, 4, 16, 64, 256, 1024, 4096};
constexpr int quick_counts[] = {1, 64, 1024};
constexpr std::pair<int64_t, int64_t> full_scaling_size{1920, 1080};
constexpr std::pair<int64_t, int64_t> quick_scaling_size{400, 225};

std::vector<int> scaling_counts(bool quick) {
  if (quick) return {std::begin(quick_counts), std::end(quick_counts)};
  return {std::begin(full_counts), std::end(full_counts)};
}

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

scene random_scene(int n, int64_t w, int64_t h) { return make_scene(sized(w, h), {}, random_spheres(n)); }

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

// Scaling rows: time only (the double reference over 4096 spheres would take
// longer than the whole bench).
void bench_scaling_ours(benchmark::State& state, int n, int64_t w, int64_t h) {
  const scene s = random_scene(n, w, h);
  const painter paint(best_path(), s, 1);
  const size_t stride = size_t(w) * 3;
  const image_band band{scratch(stride * size_t(h)), stride, pixel_format::rgb8, 0, h};
  for (auto _ : state) {
    paint.render(band);
    benchmark::ClobberMemory();
  }
  state.counters["spheres"] = n;
}

void bench_scaling_embree(benchmark::State& state, int n, int64_t w, int64_t h) {
  const scene s = random_scene(n, w, h);
  const embree_peer peer(s);
  if (!peer.error().empty()) {
    state.SkipWithError(peer.error().c_str());
    return;
  }
  const size_t stride = size_t(w) * 3;
  const image_band band{scratch(stride * size_t(h)), stride, pixel_format::rgb8, 0, h};
  for (auto _ : state) {
    peer.render(band, embree_peer::mode::packet16);
    benchmark::ClobberMemory();
  }
  state.counters["spheres"] = n;
}

std::string random_name(int n) { return "random-" + std::to_string(n); }

std::optional<double> ns_per_px(const run_table& t, const std::string& row, int64_t w, int64_t h) {
  const auto s = t.seconds(row + "|");
  if (!s) return std::nullopt;
  return *s * 1e9 / (double(w) * double(h));
}

std::string cell(std::optional<double> v, const char* fmt = "%10.2f") {
  char buf[32];
  if (!v) return "         -";
  std::snprintf(buf, sizeof buf, fmt, *v);
  return buf;
}

}  // namespace

std::vector<sphere> random_spheres(int n) {
  std::mt19937 gen(20261122u);
  // [0, 1) from the top 24 bits of one word: exact in float and double.
  auto unit = [&gen] { return double(gen() >> 8) * 0x1p-24; };
  std::vector<sphere> out;
  out.reserve(size_t(n));
  for (int k = 0; k < n; ++k) {
    const double depth = 2.0 + 6.0 * unit();
    const double x = (2.0 * unit() - 1.0) * 0.9 * (16.0 / 9.0) * depth;
    const double y = (2.0 * unit() - 1.0) * 0.9 * depth;
    const double r = 0.05 + 0.1 * unit();
    sphere s;
    s.center = point3(x, y, -depth);
    s.radius = r;
    s.shade = shading::normal;
    out.push_back(s);
  }
  return out;
}

void register_embree_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes, bool quick) {
  for (std::string_view sv : builtin_scene_names()) {
    const std::string name(sv);
    if (builtin_spheres(name)->empty()) continue;
    for (const auto& [w, h] : sizes)
      for (auto m : {embree_peer::mode::packet16, embree_peer::mode::single})
        benchmark::RegisterBenchmark(scene_row_name(mode_name(m), "float", name, w, h, 1, "rgb8").c_str(),
                                     bench_embree, name, w, h, m)
            ->Unit(benchmark::kMicrosecond);
  }
  const auto [w, h] = quick ? quick_scaling_size : full_scaling_size;
  for (int n : scaling_counts(quick)) {
    const path& best = best_path();
    benchmark::RegisterBenchmark(
        scene_row_name(best.backend, to_string(best.prec), random_name(n), w, h, 1, "rgb8").c_str(),
        bench_scaling_ours, n, w, h)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(scene_row_name("embree16", "float", random_name(n), w, h, 1, "rgb8").c_str(),
                                 bench_scaling_embree, n, w, h)
        ->Unit(benchmark::kMicrosecond);
  }
}

void print_embree_summary(std::ostream& os, const run_table& table, int64_t w, int64_t h, bool quick) {
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

  const auto [sw, sh] = quick ? quick_scaling_size : full_scaling_size;
  std::map<int, std::optional<double>> ours_at, embree_at;
  bool any_scaling = false;
  for (int n : scaling_counts(quick)) {
    ours_at[n] = ns_per_px(table, scene_row_name(best.backend, prec, random_name(n), sw, sh, 1, "rgb8"), sw, sh);
    embree_at[n] = ns_per_px(table, scene_row_name("embree16", "float", random_name(n), sw, sh, 1, "rgb8"), sw, sh);
    any_scaling = any_scaling || ours_at[n] || embree_at[n];
  }
  if (!any_scaling) return;
  os << "\nScaling: N random spheres (random_spheres), " << sw << "x" << sh
     << ", 1 thread, rgb8, ns/px\n";
  std::snprintf(line, sizeof line, "  %6s %14s %10s %12s\n", "N", ours_label.c_str(), "embree16",
                "ours/embree");
  os << line;
  for (int n : scaling_counts(quick)) {
    std::optional<double> ratio;
    if (ours_at[n] && embree_at[n]) ratio = *ours_at[n] / *embree_at[n];
    std::snprintf(line, sizeof line, "  %6d %14s %10s %12s\n", n, cell(ours_at[n]).c_str(),
                  cell(embree_at[n]).c_str(), cell(ratio, "%11.2fx").c_str());
    os << line;
  }
  auto growth = [&](std::map<int, std::optional<double>>& m, int a, int b) -> std::optional<double> {
    if (!m.count(a) || !m.count(b) || !m[a] || !m[b]) return std::nullopt;
    return *m[b] / *m[a];
  };
  const int from = quick ? 1 : 16, to = 1024;
  const auto g_ours = growth(ours_at, from, to), g_embree = growth(embree_at, from, to);
  if (g_ours || g_embree) {
    os << "  growth N=" << from << " -> " << to << ": ours" << cell(g_ours, "%7.1fx") << ", embree16"
       << cell(g_embree, "%7.1fx") << (quick ? "  (--quick has no N=16)" : "") << "\n";
  }
}

}  // namespace raycast::bench
