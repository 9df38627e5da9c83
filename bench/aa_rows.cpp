#include "aa_rows.h"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "book_ch7.h"
#include "errors.h"
#include "rows.h"
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

// The row's error against the reference, ns_per_sample, and how the
// reference was had: ref_built_s on ref_threads threads, ref_samples a pixel,
// ref_cached 1 read from the cache, 0 computed and cached now, -1 not cached.
void set_aa_counters(benchmark::State& state, const float* image, const aa_reference& ref, double samples) {
  const image_error e = measure_image_error(image, ref.rgb);
  state.counters["rms_err"] = e.rmse;
  state.counters["max_abs_err"] = e.max_abs;
  state.counters["ns_per_sample"] = state.counters["ns_per_px"] / samples;
  state.counters["ref_built_s"] = ref.build_seconds;
  state.counters["ref_threads"] = ref.threads;
  state.counters["ref_samples"] = ref.spec.samples;
  state.counters["ref_cached"] = ref.from_cache ? 1 : ref.file.empty() ? -1 : 0;
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
  time_pixels(state, double(w * h), [&] { r.render(band); });
  set_aa_counters(state, static_cast<const float*>(band.data), ref, samples);
}

// The book's ch. 7 program (bench/book_ch7.h) on world: samples_per_pixel
// jittered rays a pixel (rand()), double, one thread; its averaged colour
// against the same converged reference as ours (its jitter covers the same
// square, (i + rand) / (W - 1)).
void bench_book7(benchmark::State& state, int w, int h, int spp) {
  const aa_reference& ref = reference_for("world");
  book_ch7_image img;
  time_pixels(state, double(w * h), [&] {
    img = render_book_ch7(w, h, spp);
    benchmark::DoNotOptimize(img.rgb.data());
  });
  set_aa_counters(state, img.rgb.data(), ref, spp);
}

// A region of a many-sample frame (--region): the frame's camera and keys,
// only the window's pixels rendered. ns_per_px counts the window's pixels,
// so a region whose cost is in proportion to its pixels shows the whole
// frame's ns_per_px.
struct window {
  int64_t x0, y0, x1, y1;
};

void bench_region(benchmark::State& state, int64_t w, int64_t h, uint32_t samples, window win) {
  api::camera cp;
  cp.width = w;
  cp.height = h;
  const scene s = raycast::make_scene(api::scene{cp, {}, *builtin_spheres("world"), std::nullopt, {}});
  render_options o;
  o.which = best_backend();
  o.threads = 1;
  o.samples = samples;
  const renderer r(s, o);
  const int64_t rw = win.x1 - win.x0, rh = win.y1 - win.y0;
  const size_t stride = size_t(rw) * bytes_per_pixel(pixel_format::rgb8);
  const image_band band{scratch(stride * size_t(rh)), stride, pixel_format::rgb8, win.y0, win.y1, win.x0, win.x1};
  time_pixels(state, double(rw * rh), [&] { r.render(band); });
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
  const std::string size = size_text(cfg.width, cfg.height);
  auto fields = [&](const std::string& backend, const std::string& sampler, const std::string& scene, int64_t n) {
    return "kind=aa backend=" + backend + (sampler.empty() ? "" : " sampler=" + sampler) + " scene=" + scene +
           " size=" + size + " samples=" + std::to_string(n);
  };
  for (const std::string& sc : cfg.scenes)
    for (sampler_kind k : cfg.samplers)
      for (int64_t n : cfg.samples) {
        const std::string sampler(to_string(k));
        add_row("aa/" + cfg.backend + "/" + sampler + "/" + sc + "/" + size + "/s" + std::to_string(n),
                fields(cfg.backend, sampler, sc, n), benchmark::kMillisecond, bench_aa, sc, k, uint32_t(n));
      }
  add_row("aa/book7/world/" + size + "/s" + std::to_string(cfg.book_samples),
          fields("book7", "", "world", cfg.book_samples), benchmark::kMillisecond, bench_book7, int(cfg.width),
          int(cfg.height), cfg.book_samples);
  // region/BACKEND/world/WxH/s16/PART: the four quadrants of a frame 4x the
  // rows' size, at 16 samples, and the frame itself (PART full): together the
  // quadrants are the frame's pixels.
  const int64_t W = 4 * cfg.width, H = 4 * cfg.height;
  const std::string base = "region/" + cfg.backend + "/world/" + size_text(W, H) + "/s16/";
  const int64_t xs[] = {0, W / 2 - 7, W}, ys[] = {0, H / 2 + 5, H};  // edges inside batches
  for (int q = -1; q < 4; ++q) {
    const std::string part = q < 0 ? "full" : "q" + std::to_string(q);
    const window win = q < 0 ? window{0, 0, W, H} : window{xs[q % 2], ys[q / 2], xs[q % 2 + 1], ys[q / 2 + 1]};
    add_row(base + part, "kind=region size=" + size_text(W, H) + " samples=16 part=" + part,
            benchmark::kMillisecond, bench_region, W, H, uint32_t(16), win);
  }
}

}  // namespace raycast::bench
