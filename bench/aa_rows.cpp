#include "aa_rows.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "aa_stats.h"
#include "book_ch7.h"
#include "errors.h"
#include "report.h"
#include "render/render.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

// The reference's seed: not the rows' seed (0), so that its jitter shares no
// random numbers with the stratified rows it measures.
constexpr uint64_t reference_seed = 0x5eed0aa5;

aa_config& config() {
  static aa_config cfg;
  return cfg;
}

std::map<std::string, std::unique_ptr<aa_reference>>& references() {
  static std::map<std::string, std::unique_ptr<aa_reference>> refs;
  return refs;
}

// Loaded or computed the first time a row of the scene asks, outside any timed loop.
const aa_reference& reference_for(const std::string& scene) {
  auto& refs = references();
  auto it = refs.find(scene);
  if (it == refs.end()) {
    const aa_config& cfg = config();
    auto ref = std::make_unique<aa_reference>(
        cached_aa_reference(cfg.reference_dir, aa_reference_spec_for(cfg, scene)));
    it = refs.emplace(scene, std::move(ref)).first;
  }
  return *it->second;
}

void set_aa_counters(benchmark::State& state, const float* image, const aa_reference& ref) {
  const image_error e = measure_image_error(image, ref.rgb);
  state.counters["rms_err"] = e.rmse;
  state.counters["max_abs_err"] = e.max_abs;
}

void bench_aa(benchmark::State& state, std::string scene_name, sampler_kind kind, uint32_t samples) {
  const aa_reference& ref = reference_for(scene_name);
  const scene s = aa_scene(ref.spec);
  render_options o;
  o.which = best_backend();
  o.threads = 1;
  o.samples = samples;
  o.sampler = kind;
  o.seed = 0;
  const renderer r(s, o);
  const int64_t w = ref.spec.width, h = ref.spec.height;
  const size_t stride = size_t(w) * bytes_per_pixel(pixel_format::rgb_f32);
  const image_band band{scratch(stride * size_t(h)), stride, pixel_format::rgb_f32, 0, h};
  for (auto _ : state) {
    r.render(band);
    benchmark::ClobberMemory();
  }
  set_aa_counters(state, static_cast<const float*>(band.data), ref);
}

// The book's ch. 7 program (bench/book_ch7.h) on world: samples_per_pixel
// jittered rays a pixel (rand()), double, one thread; its averaged colour
// against the same converged reference as ours (its jitter covers the same
// square, (i + rand) / (W - 1)).
void bench_book7(benchmark::State& state, int w, int h, int spp) {
  const aa_reference& ref = reference_for("world");
  book_ch7_image img;
  for (auto _ : state) {
    img = render_book_ch7(w, h, spp);
    benchmark::DoNotOptimize(img.rgb.data());
    benchmark::ClobberMemory();
  }
  set_aa_counters(state, img.rgb.data(), ref);
}

// A region of a many-sample frame (--region): the frame's camera and keys,
// only the window's pixels rendered. ns_per_px counts the window's pixels,
// so a region whose cost is in proportion to its pixels shows the whole
// frame's ns_per_px.
struct window {
  int64_t x0, y0, x1, y1;
};

void bench_region(benchmark::State& state, int64_t w, int64_t h, uint32_t samples, window win) {
  camera_params cp;
  cp.image_width = w;
  cp.image_height = h;
  const scene s = make_scene(scene_params{cp, {}, *builtin_spheres("world")});
  render_options o;
  o.which = best_backend();
  o.threads = 1;
  o.samples = samples;
  const renderer r(s, o);
  const int64_t rw = win.x1 - win.x0, rh = win.y1 - win.y0;
  const size_t stride = size_t(rw) * bytes_per_pixel(pixel_format::rgb8);
  const image_band band{scratch(stride * size_t(rh)), stride, pixel_format::rgb8, win.y0, win.y1, win.x0, win.x1};
  for (auto _ : state) {
    r.render(band);
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_px"] = benchmark::Counter(double(rw * rh) * 1e-9,
                                                   benchmark::Counter::kIsIterationInvariantRate |
                                                       benchmark::Counter::kInvert);
}

}  // namespace

aa_config aa_config_for(bool quick, const std::string& reference_dir) {
  aa_config cfg;
  if (quick) {
    cfg.width = 96;
    cfg.height = 54;
    cfg.samples = {1, 4, 16};
    cfg.reference_samples = 4096;
  }
  cfg.reference_dir = reference_dir;
  cfg.backend = std::string(to_string(best_backend()));
  return cfg;
}

aa_reference_spec aa_reference_spec_for(const aa_config& cfg, const std::string& scene) {
  return {scene, cfg.width, cfg.height, cfg.reference_samples, sampler_kind::stratified, reference_seed};
}

void register_aa_rows(const aa_config& cfg) {
  config() = cfg;
  for (const std::string& sc : cfg.scenes)
    for (sampler_kind k : cfg.samplers)
      for (int64_t n : cfg.samples)
        benchmark::RegisterBenchmark(
            aa_row_name(cfg.backend, std::string(to_string(k)), sc, cfg.width, cfg.height, n).c_str(),
            bench_aa, sc, k, uint32_t(n))
            ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(aa_row_name("book7", "", "world", cfg.width, cfg.height, cfg.book_samples).c_str(),
                               bench_book7, int(cfg.width), int(cfg.height), cfg.book_samples)
      ->Unit(benchmark::kMillisecond);
  for (const region_row& row : region_rows(cfg))
    benchmark::RegisterBenchmark(row.name.c_str(), bench_region, row.width, row.height, row.samples,
                                 window{row.x0, row.y0, row.x1, row.y1})
        ->Unit(benchmark::kMillisecond);
}

std::vector<region_row> region_rows(const aa_config& cfg) {
  // The four quadrants of a frame 4x the rows' size, at 16 samples, and the
  // frame itself: together the quadrants are the frame's pixels.
  const int64_t W = 4 * cfg.width, H = 4 * cfg.height;
  const std::string base = "region/" + cfg.backend + "/world/" + std::to_string(W) + "x" + std::to_string(H) + "/s16/";
  std::vector<region_row> rows = {{base + "full", W, H, 16, 0, 0, W, H}};
  const int64_t xs[] = {0, W / 2 - 7, W}, ys[] = {0, H / 2 + 5, H};  // edges inside batches
  for (int q = 0; q < 4; ++q)
    rows.push_back({base + "q" + std::to_string(q), W, H, 16, xs[q % 2], ys[q / 2], xs[q % 2 + 1], ys[q / 2 + 1]});
  return rows;
}

std::vector<const aa_reference*> aa_references_used() {
  std::vector<const aa_reference*> out;
  for (const auto& [scene, ref] : references()) out.push_back(ref.get());
  return out;
}

}  // namespace raycast::bench
