#include "render.h"

#include <algorithm>

#include <omp.h>

#include "reference.h"

namespace raycast {

std::string_view to_string(backend b) {
  switch (b) {
    case backend::automatic: return "auto";
    case backend::reference: return "reference";
    case backend::scalar: return "scalar";
  }
  return "?";
}

std::string_view to_string(precision p) { return p == precision::exact ? "exact" : "fast"; }

std::optional<backend> parse_backend(std::string_view name) {
  for (backend b : {backend::automatic, backend::reference, backend::scalar})
    if (name == to_string(b)) return b;
  return std::nullopt;
}

std::optional<precision> parse_precision(std::string_view name) {
  for (precision p : {precision::exact, precision::fast})
    if (name == to_string(p)) return p;
  return std::nullopt;
}

std::optional<std::string> backend_unavailable(backend) { return std::nullopt; }

backend best_backend() { return backend::scalar; }

int available_cores() { return std::max(1, omp_get_num_procs()); }

renderer::renderer(const scene& s, const render_options& opts)
    : scene_(s),
      fscene_(prepare_float_scene(s)),
      which_(opts.which == backend::automatic ? best_backend() : opts.which),
      prec_(opts.prec),
      threads_(opts.threads > 0 ? opts.threads : available_cores()) {
  if (auto why = backend_unavailable(which_)) throw unsupported_backend(*why);
}

void renderer::render_rows(const image_band& band, int64_t r0, int64_t r1) const {
  image_band part = band;
  part.data = band.row(r0);
  part.row_begin = r0;
  part.row_end = r1;
  switch (which_) {
    case backend::reference: render_reference(scene_, part); break;
    case backend::automatic:
    case backend::scalar: render_scalar(fscene_, prec_, part); break;
  }
}

void renderer::render(const image_band& band) const {
  const int64_t rows = band.row_end - band.row_begin;
  if (rows <= 0) return;
  // Bands of consecutive rows, a few per thread so uneven cores even out.
  const int64_t nthreads = std::min<int64_t>(threads_, rows);
  if (nthreads <= 1) {
    render_rows(band, band.row_begin, band.row_end);
    return;
  }
  const int64_t chunks = std::min<int64_t>(rows, nthreads * 4);
#pragma omp parallel for schedule(dynamic, 1) num_threads(int(nthreads))
  for (int64_t c = 0; c < chunks; ++c) {
    const int64_t r0 = band.row_begin + rows * c / chunks;
    const int64_t r1 = band.row_begin + rows * (c + 1) / chunks;
    render_rows(band, r0, r1);
  }
}

}  // namespace raycast
