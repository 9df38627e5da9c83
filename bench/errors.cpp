#include "errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>


namespace raycast::bench {

std::string path::label() const { return backend + "/" + std::string(to_string(prec)); }

std::vector<path> available_paths() {
  std::vector<path> paths;
  auto add_core = [&](backend b) {
    if (backend_unavailable(b)) return;
    for (precision p : {precision::exact, precision::fast}) {
      if (b == backend::reference && p != precision::exact) continue;
      paths.push_back({std::string(to_string(b)), b, p, false});
    }
  };
  add_core(backend::reference);
  add_core(backend::scalar);
  paths.push_back({"autovec", backend::reference, precision::exact, true});
  for (backend b : simd_backends) add_core(b);
  return paths;
}

std::vector<skipped_backend> skipped_backends() {
  std::vector<skipped_backend> out;
  for (backend b : all_backends)
    if (auto why = backend_unavailable(b)) out.push_back({std::string(to_string(b)), *why});
  return out;
}

painter::painter(const path& p, const scene& s, int threads, unsigned shortcuts)
    : threads_(threads) {
  if (!p.autovec) {
    render_options o{p.core, p.prec, threads};
    o.shortcuts = shortcuts;
    core_ = std::make_unique<renderer>(s, o);
    return;
  }
  const camera& c = s.cam;
  autovec_.width = c.image_width;
  autovec_.height = c.image_height;
  autovec_.viewport_width = float(c.viewport_width);
  autovec_.viewport_height = float(c.viewport_height);
  autovec_.focal_length = float(c.focal_length);
  for (int k = 0; k < 3; ++k) {
    autovec_.origin[k] = float(c.origin[k]);
    autovec_.bottom[k] = float(s.sky.bottom[k]);
    autovec_.top[k] = float(s.sky.top[k]);
  }
}

void painter::render(const image_band& band) const {
  if (core_) {
    core_->render(band);
    return;
  }
  autovec_render_rows(autovec_, band.format == pixel_format::rgb_f32, band.data, band.stride,
                      band.row_begin, band.row_end, threads_);
}

namespace {

constexpr int64_t band_rows = 16;

// Compares rows [r0, r1) of every path with the reference, adding to acc.
void compare_band(const scene& s, const std::vector<path>& paths,
                  const std::vector<std::unique_ptr<painter>>& painters, int64_t r0, int64_t r1,
                  std::vector<float>& outf, std::vector<unsigned char>& out8,
                  std::vector<error_stats>& acc) {
  const int64_t W = s.cam.image_width;
  const raycast_test::reference_band ref(s, r0, r1);
  for (size_t p = 0; p < paths.size(); ++p) {
    if (!paths[p].autovec && paths[p].core == backend::reference) continue;  // the oracle
    painters[p]->render(image_band{outf.data(), size_t(W) * 12, pixel_format::rgb_f32, r0, r1});
    painters[p]->render(image_band{out8.data(), size_t(W) * 3, pixel_format::rgb8, r0, r1});
    ref.compare(outf.data(), out8.data(), acc[p]);
  }
}

}  // namespace

std::vector<error_stats> measure_errors(const scene& s, const std::vector<path>& paths) {
  std::vector<std::unique_ptr<painter>> painters;
  for (const path& p : paths) painters.push_back(std::make_unique<painter>(p, s, 1));
  const int64_t H = s.cam.image_height;
  const int64_t bands = (H + band_rows - 1) / band_rows;
  std::vector<error_stats> total(paths.size());
#pragma omp parallel num_threads(available_cores())
  {
    std::vector<error_stats> mine(paths.size());
    const size_t n = size_t(s.cam.image_width * std::min(H, band_rows) * 3);
    std::vector<float> outf(n);
    std::vector<unsigned char> out8(n);
#pragma omp for schedule(dynamic, 1)
    for (int64_t b = 0; b < bands; ++b)
      compare_band(s, paths, painters, b * band_rows, std::min(H, (b + 1) * band_rows), outf, out8,
                   mine);
#pragma omp critical
    for (size_t p = 0; p < paths.size(); ++p) total[p].merge(mine[p]);
  }
  return total;
}

// One buffer for every row, grown when a row needs more and touched once, so
// that no timed iteration pays for page faults.
unsigned char* scratch(size_t bytes) {
  static std::unique_ptr<unsigned char[]> buf;
  static size_t capacity = 0;
  if (bytes > capacity) {
    buf.reset();
    buf.reset(new unsigned char[bytes]);
    std::memset(buf.get(), 0, bytes);
    capacity = bytes;
  }
  return buf.get();
}

}  // namespace raycast::bench
