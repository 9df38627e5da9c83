#include "errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "reference.h"

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

painter::painter(const path& p, const scene& s, int threads, unsigned omit) : threads_(threads) {
  if (!p.autovec) {
    render_options o{p.core, p.prec, threads};
    o.omit = omit;
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

scene make_scene(const camera_params& cam, const raycast::sky& sky) {
  return scene{make_camera(cam), sky};
}

namespace {

// Per-path sums over some bands; merged at the end.
struct partial {
  double max_abs = 0, sum_sq = 0;
  int max_lsb = 0;
  int64_t mismatches = 0, nans = 0;

  void merge(const partial& o) {
    max_abs = std::max(max_abs, o.max_abs);
    sum_sq += o.sum_sq;
    max_lsb = std::max(max_lsb, o.max_lsb);
    mismatches += o.mismatches;
    nans += o.nans;
  }
};

constexpr int64_t band_rows = 16;

// One thread's band images: the reference in double and bytes, a path's output.
struct band_images {
  std::vector<double> ref;
  std::vector<unsigned char> ref8, out8;
  std::vector<float> outf;
  explicit band_images(size_t n) : ref(n), ref8(n), out8(n), outf(n) {}
};

// Compares rows [r0, r1) of every path with the reference, adding to acc.
void compare_band(const scene& s, const std::vector<path>& paths,
                  const std::vector<std::unique_ptr<painter>>& painters, int64_t r0, int64_t r1,
                  band_images& img, std::vector<partial>& acc) {
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  const size_t n = size_t(W * (r1 - r0) * 3);
  double* ref = img.ref.data();
  unsigned char* ref8 = img.ref8.data();
  unsigned char* out8 = img.out8.data();
  float* outf = img.outf.data();
  for (int64_t r = r0; r < r1; ++r)
    for (int64_t i = 0; i < W; ++i) {
      const color c = reference_pixel(s, i, H - 1 - r);
      const size_t at = size_t(((r - r0) * W + i) * 3);
      for (int k = 0; k < 3; ++k) {
        ref[at + size_t(k)] = c[k];
        ref8[at + size_t(k)] = to_byte(c[k]);
      }
    }
  for (size_t p = 0; p < paths.size(); ++p) {
    if (!paths[p].autovec && paths[p].core == backend::reference) continue;  // the oracle
    painters[p]->render(image_band{outf, size_t(W) * 12, pixel_format::rgb_f32, r0, r1});
    painters[p]->render(image_band{out8, size_t(W) * 3, pixel_format::rgb8, r0, r1});
    partial& a = acc[p];
    for (size_t k = 0; k < n; ++k) {
      double e = std::abs(double(outf[k]) - ref[k]);
      if (std::isnan(outf[k])) {
        e = std::numeric_limits<double>::infinity();
        ++a.nans;
      }
      a.max_abs = std::max(a.max_abs, e);
      a.sum_sq += e * e;
      const int lsb = std::abs(int(out8[k]) - int(ref8[k]));
      a.max_lsb = std::max(a.max_lsb, lsb);
      a.mismatches += lsb != 0;
    }
  }
}

}  // namespace

std::vector<error_stats> measure_errors(const scene& s, const std::vector<path>& paths) {
  std::vector<std::unique_ptr<painter>> painters;
  for (const path& p : paths) painters.push_back(std::make_unique<painter>(p, s, 1));
  const int64_t H = s.cam.image_height;
  const int64_t bands = (H + band_rows - 1) / band_rows;
  std::vector<partial> total(paths.size());
#pragma omp parallel num_threads(available_cores())
  {
    std::vector<partial> mine(paths.size());
    band_images img(size_t(s.cam.image_width * std::min(H, band_rows) * 3));
#pragma omp for schedule(dynamic, 1)
    for (int64_t b = 0; b < bands; ++b)
      compare_band(s, paths, painters, b * band_rows, std::min(H, (b + 1) * band_rows), img, mine);
#pragma omp critical
    for (size_t p = 0; p < paths.size(); ++p) total[p].merge(mine[p]);
  }
  const double channels = double(s.cam.image_width) * double(H) * 3.0;
  std::vector<error_stats> out(paths.size());
  for (size_t p = 0; p < paths.size(); ++p) {
    const partial& t = total[p];
    out[p] = {t.max_abs, std::sqrt(t.sum_sq / channels), t.max_lsb, double(t.mismatches) / channels,
              t.nans};
  }
  return out;
}

}  // namespace raycast::bench
