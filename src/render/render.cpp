#include "render/render.h"

#include <pthread.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <omp.h>

#include "reference/reference.h"

namespace raycast {

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

// Threads for preparing a scene (kernels/float_scene.h, kernels/culling.h):
// only large scenes use more than one.
int preparation_threads(const scene& s, int threads) {
  if (s.sphere_count() < (size_t(1) << 15)) return 1;
  return threads_that_start(threads > 0 ? threads : available_cores());
}

}  // namespace

renderer::renderer(const scene& s, const render_options& opts)
    : scene_{s.cam, s.sky, {}, std::nullopt, s.light},
      fscene_(prepare_float_scene(s, preparation_threads(s, opts.threads), opts.sort_from, opts.order)),
      which_(opts.which == backend::automatic ? best_backend() : opts.which),
      prec_(opts.prec),
      threads_(opts.threads > 0 ? opts.threads : available_cores()) {
  if (auto why = backend_unavailable(which_)) throw unsupported_backend(*why);
  // Only the double reference renders from the scene's own spheres; the
  // others read the prepared float scene and keep no second copy of them
  // (a caller's arrays become a vector here, for the reference only).
  if (which_ == backend::reference) scene_.spheres = sphere_vector(s);
  if (opts.samples < 1 || opts.samples > max_samples)
    throw std::invalid_argument("samples per pixel must be 1 to " + std::to_string(max_samples));
  if (opts.samples > 1) samples_.emplace(opts.sampler, opts.samples, opts.seed);
  // A scene without spheres runs the sky kernel, untouched; one with spheres
  // the sphere kernel, which takes the shortcuts that apply to its sky. Many
  // samples per pixel run the sphere kernel's sampled path, sky or not.
  const bool spheres = !fscene_.spheres.empty();
  if (spheres || samples_) sphere_kernel_ = kernels_for(which_).spheres;
  else sky_kernel_ = kernels_for(which_).sky;
  if (sky_kernel_ || sphere_kernel_) {  // the reference needs no plan
    plan_.emplace(fscene_, prec_, opts.shortcuts);
    if (samples_) plan_->set_samples(&samples_->plan());
    // The frame's culling (kernels/culling.h), once, shared by every thread.
    // Not for the 1-lane target: it tests every sphere at every pixel, so
    // that the vector targets' culled renders are checked against a render
    // that culls nothing.
    if ((spheres || samples_) && which_ != backend::scalar) {
      rows_ = row_index::build(fscene_, samples_ ? fscene_.pixel_spread : 0.0, preparation_threads(s, threads_));
      plan_->set_rows(rows_);
    }
  }
  ao_ = sampling::make_ao_plan(opts.sampler, s.light.ao_samples, opts.seed);
  if (plan_ && fscene_.spheres.any_lit && s.light.any()) set_light(s);
}

void renderer::set_light(const scene& s) {
  if (s.light.direction) {
    const vec3 l = unit_vector(to_glm(*s.light.direction));
    for (int k = 0; k < 3; ++k) light_[k] = float(l[k]);
  }
  if (s.light.secondary()) {
    const auto start = std::chrono::steady_clock::now();
    secondary_.emplace(s, light_, ao_, preparation_threads(s, threads_));
    light_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  plan_->set_light(s.light.direction ? light_ : nullptr, secondary_ ? &secondary_->rays() : nullptr);
}

void renderer::render_rows(const image_band& band, int64_t r0, int64_t r1, bool paired) const {
  if (sphere_kernel_) return sphere_kernel_(plan_->args(), band, r0, r1);
  if (sky_kernel_) return sky_kernel_(plan_->args(), band, r0, r1, paired);
  image_band part = band;
  part.data = band.row(r0);
  part.row_begin = r0;
  part.row_end = r1;
  render_reference(scene_, part, samples_ ? &samples_->plan() : nullptr, &ao_);
}

void renderer::render(const image_band& band) const {
  const int64_t rows = band.row_end - band.row_begin;
  if (rows <= 0) return;
  // The lesson camera's image is symmetric top to bottom: when the band holds
  // both rows of each mirrored pair, the kernel renders them together
  // (kernels/kernel.h), and the work is split over the top rows of the pairs.
  const bool paired = sky_kernel_ && plan_->args().mirror &&
                      band.row_begin + band.row_end == scene_.cam.image_height &&
                      band.whole_rows(scene_.cam.image_width);
  const int64_t units = paired ? (rows + 1) / 2 : rows;
  // Bands of consecutive rows, sixteen per thread so uneven cores and uneven
  // rows (a sphere scene's sky rows cost a fraction of its ground rows) even out. A
  // thread costs tens of microseconds to start, about what 2^17 rays take
  // to render: smaller jobs (the default 400x225 sky) stay on one thread.
  const int64_t W = scene_.cam.image_width;
  // Rays: a lit hit's secondary rays count as much as its primary one.
  const int64_t per_pixel = int64_t(samples()) * (1 + (secondary_ ? int64_t(ao_.count) + secondary_->rays().shadows : 0));
  const int64_t work = rows * (band.cols_end(W) - band.col_begin) * per_pixel;
  int64_t nthreads = std::min<int64_t>({threads_, units, std::max<int64_t>(1, work >> 17)});
  if (nthreads > 1) nthreads = threads_that_start(int(nthreads));
  if (nthreads <= 1) {
    render_rows(band, band.row_begin, band.row_begin + units, paired);
    return;
  }
  const int64_t chunks = std::min<int64_t>(units, nthreads * 16);
#pragma omp parallel for schedule(dynamic, 1) num_threads(int(nthreads))
  for (int64_t c = 0; c < chunks; ++c) {
    const int64_t r0 = band.row_begin + units * c / chunks;
    const int64_t r1 = band.row_begin + units * (c + 1) / chunks;
    render_rows(band, r0, r1, paired);
  }
}

}  // namespace raycast
