#include "render.h"

#include <pthread.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

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

namespace {

// The stack size libgomp gives its threads: OMP_STACKSIZE or GOMP_STACKSIZE
// ("<n>[B|K|M|G]", kilobytes without a unit), else the pthread default.
size_t omp_stack_size() {
  for (const char* name : {"OMP_STACKSIZE", "GOMP_STACKSIZE"}) {
    const char* v = std::getenv(name);
    if (!v) continue;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(v, &end, 10);
    while (end && std::isspace(static_cast<unsigned char>(*end))) ++end;
    unsigned shift = 10;
    switch (end ? std::tolower(static_cast<unsigned char>(*end)) : 0) {
      case 'b': shift = 0; break;
      case 'm': shift = 20; break;
      case 'g': shift = 30; break;
      default: break;
    }
    if (end == v || n > (~0ull >> shift)) return ~size_t{0};
    return size_t(n << shift);
  }
  return 0;
}

// How many threads a parallel region of `wanted` can really have. libgomp
// calls exit() when it cannot start a thread (a container's pids limit,
// RLIMIT_NPROC, an OMP_STACKSIZE the address space cannot hold), which would
// end raycast with a library's line and skip every clean-up. So, once per
// process and before the first region that needs more threads than were
// proven, start that many threads with libgomp's stack size ourselves: where
// some cannot start, the regions get only as many as did (at least the
// calling thread). libgomp keeps the threads of its first region for later
// ones, so the proof holds for the rest of the run.
int threads_that_start(int wanted) {
  static std::mutex m;
  static int proven = 1, limit = 0;  // limit 0: none found yet
  const std::lock_guard<std::mutex> lock(m);
  if (limit > 0) return std::min(wanted, limit);
  if (wanted <= proven) return wanted;
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  const size_t stack = omp_stack_size();
  bool ok = stack == 0 || pthread_attr_setstacksize(&attr, stack) == 0;
  // Each thread waits on `hold` until all were tried, so they coexist.
  static pthread_mutex_t hold = PTHREAD_MUTEX_INITIALIZER;
  pthread_mutex_lock(&hold);
  std::vector<pthread_t> started;
  while (ok && int(started.size()) + 1 < wanted) {
    pthread_t t;
    ok = pthread_create(
             &t, &attr,
             [](void*) -> void* {
               pthread_mutex_lock(&hold);
               pthread_mutex_unlock(&hold);
               return nullptr;
             },
             nullptr) == 0;
    if (ok) started.push_back(t);
  }
  pthread_mutex_unlock(&hold);
  for (pthread_t t : started) pthread_join(t, nullptr);
  pthread_attr_destroy(&attr);
  const int got = int(started.size()) + 1;
  if (got < wanted) limit = got;
  proven = std::max(proven, got);
  return got;
}

}  // namespace

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
  int64_t nthreads = std::min<int64_t>({threads_, units, std::max<int64_t>(1, pixels >> 17)});
  if (nthreads > 1) nthreads = threads_that_start(int(nthreads));
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
