#include "render/render.h"

#include <algorithm>

#include <omp.h>

#include "kernels/scalar.h"
#include "reference/reference.h"

namespace raycast {

int available_cores() { return std::max(1, omp_get_num_procs()); }

renderer::renderer(const scene& s, const render_options& opts)
    : scene_(s),
      fscene_(prepare_float_scene(s)),
      which_(opts.which == backend::automatic ? best_backend() : opts.which),
      prec_(opts.prec),
      threads_(opts.threads > 0 ? opts.threads : available_cores()) {
  if (auto why = backend_unavailable(which_)) throw unsupported_backend(*why);
  // A scene without spheres runs the sky kernel, untouched; one with spheres
  // the sphere kernel, which takes no shortcuts (they are the sky's).
  const bool spheres = !fscene_.spheres.empty();
  kernel_ = spheres ? sphere_kernel_for(which_) : kernel_for(which_);
  if (kernel_)  // reference and scalar need no plan
    plan_.emplace(fscene_, prec_, spheres ? shortcut::none : opts.shortcuts);
}

void renderer::render_rows(const image_band& band, int64_t r0, int64_t r1, bool paired) const {
  if (kernel_) {
    kernel_(plan_->args(), band, r0, r1, paired);
    return;
  }
  image_band part = band;
  part.data = band.row(r0);
  part.row_begin = r0;
  part.row_end = r1;
  if (which_ == backend::reference) render_reference(scene_, part);
  else render_scalar(fscene_, prec_, part);
}

void renderer::render(const image_band& band) const {
  const int64_t rows = band.row_end - band.row_begin;
  if (rows <= 0) return;
  // The lesson camera's image is symmetric top to bottom: when the band holds
  // both rows of each mirrored pair, the kernel renders them together
  // (kernels/kernel.h), and the work is split over the top rows of the pairs.
  const bool paired = kernel_ && plan_->args().mirror &&
                      band.row_begin + band.row_end == scene_.cam.image_height;
  const int64_t units = paired ? (rows + 1) / 2 : rows;
  // Bands of consecutive rows, a few per thread so uneven cores even out. A
  // thread costs tens of microseconds to start, about what 2^17 pixels take
  // to render: smaller jobs (the default 400x225 sky) stay on one thread.
  const int64_t pixels = rows * scene_.cam.image_width;
  const int64_t nthreads =
      std::min<int64_t>({threads_, units, std::max<int64_t>(1, pixels >> 17)});
  if (nthreads <= 1) {
    render_rows(band, band.row_begin, band.row_begin + units, paired);
    return;
  }
  const int64_t chunks = std::min<int64_t>(units, nthreads * 4);
#pragma omp parallel for schedule(dynamic, 1) num_threads(int(nthreads))
  for (int64_t c = 0; c < chunks; ++c) {
    const int64_t r0 = band.row_begin + units * c / chunks;
    const int64_t r1 = band.row_begin + units * (c + 1) / chunks;
    render_rows(band, r0, r1, paired);
  }
}

}  // namespace raycast
