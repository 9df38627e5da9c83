// What every raycast-bench row shares. A row is complete by itself: its
// label carries its fields as "key=value ..." (kind, backend, precision,
// scene, size, threads, out, ...) and its counters what it measured (errors,
// ns_per_px, ...), so that bench/report.py, reading Google Benchmark's JSON,
// needs no row name parsed and no row run before another. Ratios between rows
// (speedup, vs_memset, vs_none, Embree / ours, growth in N) are the report's.
#pragma once
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace raycast::bench {

__attribute__((format(printf, 1, 2))) inline std::string strf(const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

// The directory of this program (where the build tree, or an install, keeps raycast too).
inline std::string exe_dir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  const std::string exe = n > 0 ? std::string(buf, size_t(n)) : "";
  return exe.substr(0, exe.find_last_of('/'));
}

inline std::string size_text(int64_t w, int64_t h) {
  return strf("%lldx%lld", static_cast<long long>(w), static_cast<long long>(h));
}

// Registers fn(state, args...) as the row `name` with the label `fields`.
template <class Fn, class... Args>
benchmark::internal::Benchmark* add_row(const std::string& name, const std::string& fields,
                                        benchmark::TimeUnit unit, Fn fn, Args... args) {
  return benchmark::RegisterBenchmark(name.c_str(),
                                      [=](benchmark::State& state) {
                                        fn(state, args...);
                                        state.SetLabel(fields.c_str());
                                      })
      ->Unit(unit);
}

// render/BACKEND/PRECISION[/SCENE]/WxH/tTHREADS/OUT and its fields (no
// scene: the sky, kind render; else kind scene).
struct row_id {
  std::string name, fields;
};
inline row_id render_row(const std::string& backend, const std::string& prec, const std::string& scene,
                         int64_t w, int64_t h, int threads, const std::string& out) {
  const std::string sz = size_text(w, h), t = std::to_string(threads);
  const std::string sc = scene.empty() ? "" : "/" + scene;
  return {"render/" + backend + "/" + prec + sc + "/" + sz + "/t" + t + "/" + out,
          std::string(scene.empty() ? "kind=render" : "kind=scene scene=" + scene) + " backend=" + backend +
              " precision=" + prec + " size=" + sz + " threads=" + t + " out=" + out};
}

// The timed loop of a row that draws px pixels an iteration; ns_per_px and
// Mpix_per_s from the loop's wall time, the row's real_time.
template <class Body>
void time_pixels(benchmark::State& state, double px, Body body) {
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    body();
    benchmark::ClobberMemory();
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (state.iterations() < 1 || !(s > 0)) return;
  state.counters["ns_per_px"] = s * 1e9 / (px * double(state.iterations()));
  state.counters["Mpix_per_s"] = px * double(state.iterations()) / s * 1e-6;
}

}  // namespace raycast::bench
