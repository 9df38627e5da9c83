#include "spheres.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "book_ch6.h"
#include "errors.h"
#include "rows.h"
#include "scene/builtin.h"

namespace raycast::bench {
namespace {

// The core paths (no autovec: it renders the sky only).
const std::vector<path>& core_paths() {
  static const std::vector<path> v = [] {
    std::vector<path> out;
    for (const path& p : available_paths())
      if (!p.autovec) out.push_back(p);
    return out;
  }();
  return v;
}

scene scene_of(const std::string& name, int64_t w, int64_t h) {
  return make_scene(sized(w, h), {}, *builtin_spheres(name));
}

// Errors per (scene, size): the core paths', then the book's (8-bit only).
struct scene_errors {
  std::vector<error_stats> core;
  error_stats book;
};

const scene_errors& errors_for(const std::string& name, int64_t w, int64_t h) {
  static std::map<std::tuple<std::string, int64_t, int64_t>, scene_errors> cache;
  const auto key = std::make_tuple(name, w, h);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const scene s = scene_of(name, w, h);
  scene_errors e;
  e.core = measure_errors(s, core_paths());
  if (name == "world") {
    const book_ch6 book(s);
    std::vector<unsigned char> out(size_t(w) * 3 * 16);
    for (int64_t r0 = 0; r0 < h; r0 += 16) {
      const int64_t r1 = std::min(h, r0 + 16);
      book.render(image_band{out.data(), size_t(w) * 3, pixel_format::rgb8, r0, r1});
      raycast_test::reference_band(s, r0, r1).compare(nullptr, out.data(), e.book);
    }
  }
  return cache.emplace(key, std::move(e)).first->second;
}

void set_error_counters(benchmark::State& state, const error_stats& e, bool has_float) {
  if (has_float) {
    state.counters["max_abs_err"] = e.max_abs_err;
    state.counters["rms_err"] = e.rms_err();
  }
  state.counters["max_lsb"] = e.max_lsb;
  state.counters["lsb_mismatch"] = e.lsb_mismatch();
}

void bench_scene(benchmark::State& state, std::string name, size_t path_index, int64_t w, int64_t h,
                 int threads, pixel_format format) {
  const scene_errors& e = errors_for(name, w, h);
  const scene s = scene_of(name, w, h);
  const painter paint(core_paths()[path_index], s, threads);
  const size_t stride = size_t(w) * bytes_per_pixel(format);
  const image_band band{scratch(stride * size_t(h)), stride, format, 0, h};
  time_pixels(state, double(w * h), [&] { paint.render(band); });
  set_error_counters(state, e.core[path_index], true);
}

void bench_book(benchmark::State& state, int64_t w, int64_t h) {
  const scene_errors& e = errors_for("world", w, h);
  const scene s = scene_of("world", w, h);
  const book_ch6 book(s);
  const size_t stride = size_t(w) * 3;
  const image_band band{scratch(stride * size_t(h)), stride, pixel_format::rgb8, 0, h};
  time_pixels(state, double(w * h), [&] { book.render(band); });
  set_error_counters(state, e.book, false);
}

}  // namespace

void register_sphere_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes,
                          const std::vector<int>& threads) {
  for (std::string_view sv : builtin_scene_names()) {
    const std::string name(sv);
    if (builtin_spheres(name)->empty()) continue;  // the sky's rows are render/BACKEND/...
    for (const auto& [w, h] : sizes)
      for (int t : threads)
        for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32}) {
          const std::string out = f == pixel_format::rgb8 ? "rgb8" : "f32";
          for (size_t p = 0; p < core_paths().size(); ++p) {
            const path& pa = core_paths()[p];
            const row_id r = render_row(pa.backend, std::string(to_string(pa.prec)), name, w, h, t, out);
            add_row(r.name, r.fields, benchmark::kMicrosecond, bench_scene, name, p, w, h, t, f);
          }
          if (name == "world" && t == 1 && f == pixel_format::rgb8) {
            const row_id r = render_row("book", "exact", name, w, h, t, out);
            add_row(r.name, r.fields, benchmark::kMicrosecond, bench_book, w, h);
          }
        }
  }
}

}  // namespace raycast::bench
