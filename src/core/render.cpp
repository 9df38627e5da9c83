#include "render.h"

#include <algorithm>
#include <cstdlib>
#include <new>

#include <omp.h>

#include "cpu.h"
#include "reference.h"

namespace raycast {

std::string_view to_string(backend b) {
  switch (b) {
    case backend::automatic: return "auto";
    case backend::reference: return "reference";
    case backend::scalar: return "scalar";
    case backend::sse2: return "sse2";
    case backend::avx2: return "avx2";
    case backend::avx512: return "avx512";
    case backend::neon: return "neon";
  }
  return "?";
}

std::string_view to_string(precision p) { return p == precision::exact ? "exact" : "fast"; }

std::optional<backend> parse_backend(std::string_view name) {
  if (name == to_string(backend::automatic)) return backend::automatic;
  for (backend b : all_backends)
    if (name == to_string(b)) return b;
  return std::nullopt;
}

std::optional<precision> parse_precision(std::string_view name) {
  for (precision p : {precision::exact, precision::fast})
    if (name == to_string(p)) return p;
  return std::nullopt;
}

std::optional<std::string> backend_unavailable(backend b) {
  const cpu_features& f = cpu();
#if RAYCAST_HAVE_X86_KERNELS
  switch (b) {
    case backend::sse2:
      if (!f.sse2) return std::string("this CPU cannot run SSE2");
      break;
    case backend::avx2:
      if (!f.avx2_fma) return std::string("this CPU (or OS) cannot run AVX2 + FMA");
      break;
    case backend::avx512:
      if (!f.avx512) return std::string("this CPU (or OS) cannot run AVX-512 F+BW+VL");
      break;
    default: break;
  }
#else
  if (b == backend::sse2 || b == backend::avx2 || b == backend::avx512)
    return std::string(to_string(b)) + " exists only in x86-64 builds";
#endif
#if RAYCAST_HAVE_NEON_KERNELS
  if (b == backend::neon && !f.neon) return std::string("this CPU cannot run NEON");
#else
  if (b == backend::neon) return std::string("neon exists only in AArch64 builds");
#endif
  (void)f;
  return std::nullopt;
}

backend best_backend() {
  for (backend b : {backend::avx512, backend::avx2, backend::sse2, backend::neon})
    if (!backend_unavailable(b)) return b;
  return backend::scalar;
}

void renderer::free_deleter::operator()(float* p) const { std::free(p); }

int available_cores() { return std::max(1, omp_get_num_procs()); }

renderer::renderer(const scene& s, const render_options& opts)
    : scene_(s),
      fscene_(prepare_float_scene(s)),
      which_(opts.which == backend::automatic ? best_backend() : opts.which),
      prec_(opts.prec),
      threads_(opts.threads > 0 ? opts.threads : available_cores()) {
  if (auto why = backend_unavailable(which_)) throw unsupported_backend(*why);
  switch (which_) {
#if RAYCAST_HAVE_X86_KERNELS
    case backend::sse2: kernel_ = kernels::sse2::render_rows; break;
    case backend::avx2: kernel_ = kernels::avx2::render_rows; break;
    case backend::avx512: kernel_ = kernels::avx512::render_rows; break;
#endif
#if RAYCAST_HAVE_NEON_KERNELS
    case backend::neon: kernel_ = kernels::neon::render_rows; break;
#endif
    default: return;  // reference and scalar need no tables
  }
  const float_scene& f = fscene_;
  args_.scene = &fscene_;
  args_.prec = prec_;
  // Per-column parts of the direction, in scalar.h's operations and order;
  // padded with zeros to whole 16-lane batches.
  const size_t padded = size_t(f.width + 15) / 16 * 16;
  const auto table = [padded] {
    float* p = static_cast<float*>(std::aligned_alloc(64, padded * sizeof(float)));
    if (!p) throw std::bad_alloc();
    std::fill(p, p + padded, 0.0f);
    return aligned_floats(p);
  };
  args_.axis_aligned = (opts.omit & omit_lanes) && f.axis_aligned;
  args_.mirror = args_.axis_aligned && (opts.omit & omit_mirrored);
  for (int k = 0; k < 3; ++k) {
    if (args_.axis_aligned && k > 0) break;  // the lesson camera reads x only
    col_[k] = table();
    for (int64_t i = 0; i < f.width; ++i) {
      col_[k][size_t(i)] = f.centre[k] + pixel_su(f, i) * f.horizontal[k];
    }
    args_.col[k] = col_[k].get();
  }
  if (args_.axis_aligned) {
    col_x2_ = table();
    for (size_t i = 0; i < padded; ++i) col_x2_[i] = col_[0][i] * col_[0][i];
    args_.col_x2 = col_x2_.get();
  }
  bool unit = true, lerp_exact = true;
  for (int k = 0; k < 3; ++k) {
    args_.constant[k] = (opts.omit & omit_channels) && f.bottom[k] == f.top[k];
    args_.constant_value[k] = f.bottom[k];
    const float c01 = f.bottom[k] > 0.0f ? (f.bottom[k] < 1.0f ? f.bottom[k] : 1.0f) : 0.0f;
    args_.constant_byte[k] = int32_t(c01 * 255.999f);
    unit = unit && f.lo[k] >= 0.0f && f.hi[k] <= 1.0f;
    lerp_exact = lerp_exact && f.bottom[k] + 1.0f * f.delta[k] == f.top[k];
  }
  const bool clamps = opts.omit & omit_clamps;
  args_.lerp_exact = clamps && lerp_exact;
  args_.colours_in_unit_range = clamps && unit;
}

void renderer::render_rows(const image_band& band, int64_t r0, int64_t r1, bool paired) const {
  if (kernel_) {
    kernel_(args_, band, r0, r1, paired);
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
  const bool paired = kernel_ && args_.mirror &&
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
