#include "scale_rows.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "cloud.h"
#include "embree_peer.h"
#include "errors.h"
#include "scene/scene_file.h"

namespace raycast::bench {
namespace {
using raycast_test::cloud_json;
using raycast_test::particle_cloud;

std::vector<int64_t> counts(bool quick) {
  if (quick) return {1, 1000, 10000};
  std::vector<int64_t> v;
  for (int64_t n = 1; n <= 10'000'000; n *= 10) v.push_back(n);
  return v;
}

int threads_of(bool all) { return all ? available_cores() : 1; }

std::string row(const char* who, int64_t n, bool all) {
  return strf("scale/%s/%lld/%s", who, static_cast<long long>(n), all ? "tall" : "t1");
}
std::string load_row(int64_t n) { return strf("load/%lld", static_cast<long long>(n)); }

using steady = std::chrono::steady_clock;
double seconds_since(steady::time_point t0) {
  return std::chrono::duration<double>(steady::now() - t0).count();
}

benchmark::Counter per_iteration(double v) { return {v, benchmark::Counter::kAvgIterations}; }

// Each iteration: make() builds the renderer (timed as prepare; null after
// SkipWithError when it cannot), draw(it, band) renders one frame into the
// shared buffer; it is freed untimed.
template <class Make, class Draw>
void time_frames(benchmark::State& state, const scene& s, const char* prepare, Make make, Draw draw) {
  const int64_t w = s.cam.image_width, h = s.cam.image_height;
  const image_band band{scratch(size_t(w * h) * 3), size_t(w) * 3, pixel_format::rgb8, 0, h};
  double prep = 0, render = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    auto r = make();
    prep += seconds_since(t0);
    if (!r) return;  // make() said why (SkipWithError)
    const steady::time_point t1 = steady::now();
    draw(*r, band);
    benchmark::ClobberMemory();
    render += seconds_since(t1);
    state.PauseTiming();
    r.reset();
    state.ResumeTiming();
  }
  state.counters[prepare] = per_iteration(prep);
  state.counters["render_s"] = per_iteration(render);
  state.counters["ns_per_px"] = per_iteration(render * 1e9 / double(w * h));
  state.counters["spheres"] = double(s.spheres.size());
}

void bench_ours(benchmark::State& state, int64_t n, bool all) {
  const scene s = make_scene(particle_cloud(n));
  render_options o;
  o.threads = threads_of(all);
  time_frames(
      state, s, "prepare_s", [&] { return std::make_unique<renderer>(s, o); },
      [](const renderer& r, const image_band& band) { r.render(band); });
}

void bench_embree(benchmark::State& state, int64_t n, bool all) {
  const scene s = make_scene(particle_cloud(n));
  time_frames(
      state, s, "build_s",
      [&] {
        auto peer = std::make_unique<embree_peer>(s, threads_of(all));
        if (!peer->error().empty()) {
          state.SkipWithError(peer->error().c_str());
          peer.reset();
        }
        return peer;
      },
      [](const embree_peer& p, const image_band& band) { p.render(band, embree_peer::mode::packet16); });
}

void bench_load(benchmark::State& state, int64_t n) {
  std::optional<scene_params> cloud = particle_cloud(n);
  const std::string text = cloud_json(*cloud);
  const sphere last = cloud->spheres.back();
  cloud.reset();
  double parse = 0, prep = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    auto parsed = parse_scene_file(text);
    const double p = seconds_since(t0);
    const auto* params = std::get_if<scene_params>(&parsed);
    if (!params || params->spheres.size() != size_t(n) || params->spheres.back().center != last.center ||
        params->spheres.back().radius != last.radius) {
      state.SkipWithError(params ? "the parsed cloud is not the generated one"
                                 : std::get<scene_file_error>(parsed).message.c_str());
      return;
    }
    const steady::time_point t1 = steady::now();
    std::optional<scene> s = make_scene(*params);
    parsed = scene_file_error{};  // the parsed spheres are not needed any more
    auto r = std::make_unique<renderer>(*s, render_options{});
    prep += seconds_since(t1);
    parse += p;
    state.PauseTiming();
    r.reset();
    s.reset();
    state.ResumeTiming();
  }
  state.counters["parse_ns_per_sphere"] = per_iteration(parse * 1e9 / double(n));
  state.counters["prepare_ns_per_sphere"] = per_iteration(prep * 1e9 / double(n));
  state.counters["bytes_per_sphere"] = double(text.size()) / double(n);
}

// Milliseconds, 3 or 4 significant digits, in 8 columns.
std::string ms(std::optional<double> s) {
  if (!s) return "       -";
  const double v = *s * 1e3;
  return strf(v < 10 ? "%8.3f" : v < 100 ? "%8.2f" : v < 1e4 ? "%8.1f" : "%8.0f", v);
}
std::string ratio(std::optional<double> a, std::optional<double> b) {
  if (!a || !b || !(*b > 0)) return "        ";
  const double x = *a / *b;
  return strf(x < 100 ? " %6.2fx" : " %6.0fx", x);
}

}  // namespace

void register_scale_rows(bool quick) {
  for (int64_t n : counts(quick)) {
    auto setup = [](benchmark::internal::Benchmark* b) { b->Unit(benchmark::kMillisecond); };
    for (bool all : {false, true}) {
      setup(benchmark::RegisterBenchmark(row("ours", n, all).c_str(), bench_ours, n, all));
      setup(benchmark::RegisterBenchmark(row("embree", n, all).c_str(), bench_embree, n, all));
    }
    setup(benchmark::RegisterBenchmark(load_row(n).c_str(), bench_load, n));
  }
}

void print_scale_summary(std::ostream& os, const run_table& table, bool quick) {
  struct cells {
    std::optional<double> prep, render, total, total_all, px;
  };
  auto at = [&](const char* who, const char* prepare, int64_t n) {
    cells c;
    c.prep = table.counter(row(who, n, false), prepare);
    c.render = table.counter(row(who, n, false), "render_s");
    c.total = table.seconds(row(who, n, false) + "|");
    c.total_all = table.seconds(row(who, n, true) + "|");
    c.px = table.counter(row(who, n, false), "ns_per_px");
    return c;
  };
  bool any = false;
  for (int64_t n : counts(quick))
    any = any || at("ours", "prepare_s", n).total || at("ours", "prepare_s", n).total_all ||
          at("embree", "build_s", n).total || at("embree", "build_s", n).total_all ||
          table.seconds(load_row(n) + "|");
  if (!any) return;
  const cells ours_base = at("ours", "prepare_s", 1000), embree_base = at("embree", "build_s", 1000);
  os << "\nScale: particle clouds (tests/support/cloud.h, coverage 1.5), 1920x1080, rgb8; ms (medians); tall = "
     << available_cores() << " threads\n"
     << "                  ours t1           ours      embree t1         embree  embree  speedup "
        "tall   ns/px vs 1e3  load ns/sphere\n"
     << "         N    prep  render   total    tall   build  render   total    tall   /ours    ours"
        "  embree    ours  embree   parse    prep\n";
  for (int64_t n : counts(quick)) {
    const cells o = at("ours", "prepare_s", n), e = at("embree", "build_s", n);
    auto ns = [&](const char* name) {
      const auto v = table.counter(load_row(n), name);
      return v ? strf("%8.1f", *v) : std::string("       -");
    };
    os << strf("  %8lld", static_cast<long long>(n)) << ms(o.prep) << ms(o.render) << ms(o.total)
       << ms(o.total_all) << ms(e.prep) << ms(e.render) << ms(e.total) << ms(e.total_all)
       << ratio(e.total, o.total) << ratio(o.total, o.total_all) << ratio(e.total, e.total_all)
       << ratio(o.px, ours_base.px) << ratio(e.px, embree_base.px) << ns("parse_ns_per_sphere")
       << ns("prepare_ns_per_sphere") << "\n";
  }
  os << "  total = prepare + render; embree / ours and ns/px growth at 1 thread; speedup = t1 / tall\n";
}

}  // namespace raycast::bench
