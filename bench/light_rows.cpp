#include "light_rows.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cloud.h"
#include "embree_peer.h"
#include "tachyon_peer.h"
#include "render/render.h"
#include "rows.h"

namespace raycast::bench {
namespace {

using steady = std::chrono::steady_clock;
double seconds_since(steady::time_point t0) { return std::chrono::duration<double>(steady::now() - t0).count(); }
benchmark::Counter per_iteration(double v) { return {v, benchmark::Counter::kAvgIterations}; }

// A family's scene, every sphere lit in one colour, under a directional light.
struct family {
  const char* name;
  api::scene (*make)(int64_t n);
  vec3 light;
  bool bounded_ao;  // AO distance 5 radii (the boxes), else unbounded
};
const family families[] = {
    {"box", [](int64_t n) { return raycast_test::particle_box(n); }, {0.3, 1.0, 0.6}, true},
    {"box-random", [](int64_t n) { return raycast_test::particle_box_random(n); }, {0.3, 1.0, 0.6}, true},
    {"dense", [](int64_t n) { return raycast_test::particle_cloud(n, 3.0); }, {-0.5, 1.0, 0.3}, false},
    {"cloud", [](int64_t n) { return raycast_test::particle_cloud(n, 1.5); }, {-0.5, 1.0, 0.3}, false},
};

struct variant {
  const char* name;
  uint32_t ao;
  bool unbounded = false;  // AO unbounded in a family whose AO is bounded (the boxes): Tachyon's kind
};
const variant variants[] = {{"shadows", 0}, {"shadows-ao8", 8}, {"shadows-ao8-unbounded", 8, true}};

// Whether a family's row of variant v has unbounded AO (or none): what
// Tachyon renders, whose AO has no distance.
bool unbounded(const family& f, const variant& v) { return !f.bounded_ao || v.unbounded || v.ao == 0; }

scene lit_scene(const family& f, int64_t n, const variant& v, int64_t w, int64_t h, bool secondary = true) {
  api::scene p = f.make(n);
  p.cam.width = w;
  p.cam.height = h;
  for (sphere& s : p.spheres) {
    s.shade = shading::lit;
    s.color = color(0.85, 0.6, 0.35);
  }
  p.light.direction = f.light;
  p.light.shadows = secondary;
  p.light.ao_samples = secondary ? v.ao : 0;
  if (!unbounded(f, v) && !p.spheres.empty()) p.light.ao_distance = 5 * p.spheres[0].radius;
  return make_scene(p);
}

struct frame {
  int64_t w, h;
  std::vector<unsigned char> pixels;
  image_band band() { return {pixels.data(), size_t(w) * 3, pixel_format::rgb8, 0, h}; }
};

void bench_ours(benchmark::State& state, const family* f, int64_t n, const variant* v, int64_t w, int64_t h,
                bool all) {
  const scene s = lit_scene(*f, n, *v, w, h), primary = lit_scene(*f, n, *v, w, h, false);
  render_options o;
  o.threads = all ? available_cores() : 1;
  frame fr{w, h, std::vector<unsigned char>(size_t(w * h) * 3)};
  double prep = 0, render = 0, first = 0, light = 0, lists = 0, list_s = 0, bytes = 0;
  for (auto _ : state) {
    steady::time_point t0 = steady::now();
    auto r = std::make_unique<renderer>(s, o);
    prep += seconds_since(t0);
    t0 = steady::now();
    r->render(fr.band());
    benchmark::ClobberMemory();
    render += seconds_since(t0);
    state.PauseTiming();
    light += r->light_seconds();
    lists += double(r->light_lists());
    list_s += r->light_list_seconds();
    bytes += double(r->light_bytes());
    r.reset();
    const renderer p(primary, o);
    t0 = steady::now();
    p.render(fr.band());
    first += seconds_since(t0);
    state.ResumeTiming();
  }
  state.counters["prepare_s"] = per_iteration(prep);
  state.counters["render_s"] = per_iteration(render);
  state.counters["primary_s"] = per_iteration(first);
  state.counters["light_s"] = per_iteration(light);  // of prepare_s: the far field's build
  state.counters["lists"] = per_iteration(lists);     // spheres whose near-field lists the frame gathered
  state.counters["lists_s"] = per_iteration(list_s);  // of render_s, the threads' seconds gathering them
  state.counters["light_mb"] = per_iteration(bytes * 1e-6);  // the light's structures after the frame
}

void bench_embree(benchmark::State& state, const family* f, int64_t n, const variant* v, int64_t w, int64_t h) {
  const scene s = lit_scene(*f, n, *v, w, h);
  const sampling::ao_plan ao = sampling::make_ao_plan(default_sampler, s.light.ao_samples, 0);
  frame fr{w, h, std::vector<unsigned char>(size_t(w * h) * 3)};
  double build = 0, primary = 0, shadow = 0, occlusion = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    auto peer = std::make_unique<embree_peer>(s, 1);
    build += seconds_since(t0);
    if (!peer->error().empty()) return state.SkipWithError(peer->error().c_str());
    const embree_peer::light_seconds t = peer->render_lit(fr.band(), ao);
    primary += t.primary;
    shadow += t.shadow;
    occlusion += t.ao;
    state.PauseTiming();
    peer.reset();
    state.ResumeTiming();
  }
  state.counters["build_s"] = per_iteration(build);
  state.counters["primary_s"] = per_iteration(primary);
  state.counters["shadow_s"] = per_iteration(shadow);
  state.counters["ao_s"] = per_iteration(occlusion);
  state.counters["render_s"] = per_iteration(primary + shadow + occlusion);
}

// Tachyon's frame of the same scene (tachyon_peer.h): its preprocessing
// (prepare_s) and ray tracing (render_s) by its own timers, on one thread
// or all cores; frame_mismatch: the fraction of pixels that hit a sphere in
// one picture and not the other (480x270, the same camera), once a row.
void bench_tachyon(benchmark::State& state, const family* f, int64_t n, const variant* v, int64_t w, int64_t h,
                   bool all) {
  if (tachyon_peer::program().empty())
    return state.SkipWithError("skipped: no tachyon program here (Debian: apt install tachyon)");
  const scene s = lit_scene(*f, n, *v, w, h);
  const tachyon_peer peer(s);
  const double mismatch = peer.framing_mismatch(480, 270);
  double prep = 0, render = 0;
  for (auto _ : state) {
    const tachyon_peer::timers t = peer.render(all ? available_cores() : 1, true, s.light.ao_samples);
    if (!t.error.empty()) return state.SkipWithError(t.error.c_str());
    prep += t.preprocess;
    render += t.trace;
  }
  state.counters["prepare_s"] = per_iteration(prep);
  state.counters["render_s"] = per_iteration(render);
  state.counters["frame_mismatch"] = mismatch;
}

// Ambient occlusion's Monte Carlo error against run time: a lit box of 2000
// spheres, AO distance 5 radii, no shadows, rgb_f32, one thread, against a
// converged image (sobol, converged_ao rays a hit), computed once.
struct ao_config {
  int64_t w, h;
  uint32_t converged;
};

scene ao_scene(const ao_config& c, uint32_t n) {
  scene s = lit_scene(families[0], 2000, variants[0], c.w, c.h);
  s.light.shadows = false;
  s.light.ao_samples = n;
  return s;
}

std::vector<float> render_f32(const scene& s, sampler_kind k) {
  render_options o;
  o.threads = 1;
  o.sampler = k;
  std::vector<float> px(size_t(s.cam.image_width * s.cam.image_height) * 3);
  const renderer r(s, o);
  r.render({px.data(), size_t(s.cam.image_width) * 12, pixel_format::rgb_f32, 0, s.cam.image_height});
  return px;
}

const std::vector<float>& converged(const ao_config& c) {
  static std::vector<float> image;
  if (image.empty()) {
    render_options o;
    o.threads = available_cores();
    const scene s = ao_scene(c, c.converged);
    image.resize(size_t(c.w * c.h) * 3);
    const renderer r(s, o);
    r.render({image.data(), size_t(c.w) * 12, pixel_format::rgb_f32, 0, c.h});
  }
  return image;
}

void bench_ao(benchmark::State& state, ao_config c, sampler_kind k, uint32_t n) {
  const scene s = ao_scene(c, n);
  const std::vector<float>& want = converged(c);
  std::vector<float> got;
  double t = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    got = render_f32(s, k);
    t += seconds_since(t0);
  }
  double sum = 0, most = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    const double e = double(got[i]) - double(want[i]);
    sum += e * e;
    most = std::max(most, std::abs(e));
  }
  state.counters["ns_per_px"] = per_iteration(t * 1e9 / double(c.w * c.h));
  state.counters["rms_err"] = std::sqrt(sum / double(got.size()));
  state.counters["max_abs_err"] = most;
  state.counters["converged_ao"] = c.converged;
}

}  // namespace

void register_ao_rows(bool quick) {
  const ao_config c = quick ? ao_config{160, 90, 256} : ao_config{320, 180, 4096};
  const std::vector<uint32_t> counts = quick ? std::vector<uint32_t>{1, 4, 16}
                                             : std::vector<uint32_t>{1, 2, 4, 8, 16, 32, 64, 128, 256};
  for (sampler_kind k : {sampler_kind::random, sampler_kind::stratified, sampler_kind::sobol})
    for (uint32_t n : counts) {
      const std::string sampler(to_string(k)), size = size_text(c.w, c.h);
      add_row(strf("ao/%s/box2000/%s/ao%u", sampler.c_str(), size.c_str(), n),
              strf("kind=ao sampler=%s scene=box2000 size=%s ao=%u", sampler.c_str(), size.c_str(), n),
              benchmark::kMillisecond, bench_ao, c, k, n);
    }
}

void register_light_rows(bool quick) {
  register_ao_rows(quick);
  const int64_t w = quick ? 640 : 1920, h = quick ? 360 : 1080;
  for (const family& f : families)
    for (int64_t n : quick ? std::vector<int64_t>{1000} : std::vector<int64_t>{10'000, 100'000, 1'000'000, 10'000'000}) {
      if (quick && f.name != std::string("box")) continue;
      for (const variant& v : variants) {
        if (v.unbounded && !f.bounded_ao) continue;  // the clouds' AO is unbounded already
        const std::string base = strf("light/%s/%%s/%lld/%s/%%s", f.name, static_cast<long long>(n), v.name);
        const std::string fields = strf("kind=light family=%s spheres=%lld variant=%s size=%s", f.name,
                                        static_cast<long long>(n), v.name, size_text(w, h).c_str());
        for (bool all : {false, true})
          add_row(strf(base.c_str(), "ours", all ? "tall" : "t1"), fields + " peer=ours threads=" + (all ? "all" : "1"),
                  benchmark::kMillisecond, bench_ours, &f, n, &v, w, h, all);
        add_row(strf(base.c_str(), "embree", "t1"), fields + " peer=embree threads=1", benchmark::kMillisecond,
                bench_embree, &f, n, &v, w, h);
        if (!unbounded(f, v) || n > 1'000'000) continue;  // Tachyon: unbounded AO only, and minutes a frame beyond
        for (bool all : {false, true})
          add_row(strf(base.c_str(), "tachyon", all ? "tall" : "t1"),
                  fields + " peer=tachyon threads=" + (all ? "all" : "1"), benchmark::kMillisecond, bench_tachyon, &f,
                  n, &v, w, h, all);
      }
    }
}

}  // namespace raycast::bench
