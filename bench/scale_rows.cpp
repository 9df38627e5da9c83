#include "scale_rows.h"

#include <benchmark/benchmark.h>
#include <simdjson.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "cloud.h"
#include "embree_peer.h"
#include "errors.h"
#include "rows.h"
#include "formats/json.h"

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

// The scenes of the scale rows (tests/support/cloud.h): the sparse particle
// cloud (coverage 1.5), the dense one (3: about three spheres behind each
// pixel), the packed box seen from a corner (a ray passes dozens) and the
// same box along an axis through an orthographic camera.
struct family {
  const char* name;
  api::scene (*make)(int64_t n);
  int64_t from;  // the smallest N of the family's rows
};
const family families[] = {
    {"cloud", [](int64_t n) { return particle_cloud(n, 1.5); }, 1},
    {"dense", [](int64_t n) { return particle_cloud(n, 3.0); }, 1000},
    {"box", [](int64_t n) { return raycast_test::particle_box(n); }, 1000},
    {"box-ortho", [](int64_t n) { return raycast_test::particle_box(n, true); }, 1000},
};

std::string row(const family& f, const char* who, int64_t n, bool all) {
  return strf("scale/%s/%s/%lld/%s", f.name, who, static_cast<long long>(n), all ? "tall" : "t1");
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

void bench_ours(benchmark::State& state, const family* f, int64_t n, bool all) {
  const scene s = raycast::make_scene(f->make(n));
  render_options o;
  o.threads = threads_of(all);
  time_frames(
      state, s, "prepare_s", [&] { return std::make_unique<renderer>(s, o); },
      [](const renderer& r, const image_band& band) { r.render(band); });
}

void bench_embree(benchmark::State& state, const family* f, int64_t n, bool all) {
  const scene s = raycast::make_scene(f->make(n));
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

// simdjson's own floor for the cloud's text: a bare On-Demand loop that
// reads each sphere's four numbers and checks nothing (the peer of our
// parse, which validates, names paths and keeps every sphere); their sum, so
// the loop is not optimized away.
double bare_parse(const simdjson::padded_string& text) {
  simdjson::ondemand::parser parser;
  double sum = 0;
  simdjson::ondemand::document doc = parser.iterate(text);
  for (auto field : doc.get_object()) {
    if (std::string_view(field.unescaped_key()) != "spheres") continue;
    for (simdjson::ondemand::object ball : field.value().get_array())
      for (auto f : ball) {
        const std::string_view key = f.unescaped_key();
        if (key == "center")
          for (double x : f.value().get_array()) sum += x;
        else if (key == "radius")
          sum += double(f.value());
      }
  }
  return sum;
}

void bench_load(benchmark::State& state, int64_t n) {
  std::optional<api::scene> cloud = particle_cloud(n);
  const std::string text = cloud_json(*cloud);
  const sphere last = cloud->spheres.back();
  cloud.reset();
  const simdjson::padded_string padded(text);
  render_options one_thread;  // as the parse: the preparation on one thread
  one_thread.threads = 1;
  double parse = 0, prep = 0, bare = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    auto parsed = parse_scene_file(text);
    const double p = seconds_since(t0);
    auto* params = std::get_if<api::scene>(&parsed);
    if (!params || params->spheres.size() != size_t(n) || params->spheres.back().center != last.center ||
        params->spheres.back().radius != last.radius) {
      state.SkipWithError(params ? "the parsed cloud is not the generated one"
                                 : std::get<scene_file_error>(parsed).message.c_str());
      return;
    }
    const steady::time_point t1 = steady::now();
    std::optional<scene> s = raycast::make_scene(std::move(*params));  // the spheres moved, as raycast does
    parsed = scene_file_error{};  // the parsed spheres are not needed any more
    auto r = std::make_unique<renderer>(*s, one_thread);
    prep += seconds_since(t1);
    parse += p;
    state.PauseTiming();
    r.reset();
    s.reset();
    const steady::time_point t2 = steady::now();
    benchmark::DoNotOptimize(bare_parse(padded));
    bare += seconds_since(t2);
    state.ResumeTiming();
  }
  state.counters["parse_ns_per_sphere"] = per_iteration(parse * 1e9 / double(n));
  state.counters["bare_simdjson_ns_per_sphere"] = per_iteration(bare * 1e9 / double(n));
  state.counters["prepare_ns_per_sphere"] = per_iteration(prep * 1e9 / double(n));
  state.counters["bytes_per_sphere"] = double(text.size()) / double(n);
}

}  // namespace

void register_scale_rows(bool quick) {
  for (const family& f : families)
    for (int64_t n : counts(quick)) {
      if (n < f.from) continue;
      for (bool all : {false, true})
        for (const char* peer : {"ours", "embree"})
          add_row(row(f, peer, n, all),
                  strf("kind=scale family=%s peer=%s spheres=%lld threads=%s", f.name, peer,
                       static_cast<long long>(n), all ? "all" : "1"),
                  benchmark::kMillisecond, peer[0] == 'o' ? bench_ours : bench_embree, &f, n, all);
    }
  for (int64_t n : counts(quick))
    add_row(load_row(n), strf("kind=load spheres=%lld", static_cast<long long>(n)), benchmark::kMillisecond,
            bench_load, n);
}

}  // namespace raycast::bench
