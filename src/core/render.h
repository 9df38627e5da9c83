// The one entry point for rendering: pick a backend, prepare the scene once,
// then fill bands of rows on as many threads as asked.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <memory>

#include "float_scene.h"
#include "kernels/kernel.h"
#include "image.h"
#include "scalar.h"
#include "scene.h"

namespace raycast {

enum class backend : uint8_t {
  automatic,  // the best one this CPU runs
  reference,  // double, the oracle (reference.h)
  scalar,     // float, one pixel at a time (scalar.h)
  sse2,       // 8 pixels a batch as two 4-lane halves; any x86-64
  avx2,       // 8 pixels a batch; AVX2 + FMA
  avx512,     // 16 pixels a batch; AVX-512 F + BW + VL
  neon,       // 8 pixels a batch as two 4-lane halves; any AArch64
};

// Every backend, x86's best last, then AArch64's. A build has the SIMD
// backends of its own architecture only; backend_unavailable says why not.
inline constexpr backend all_backends[] = {backend::reference, backend::scalar, backend::sse2,
                                           backend::avx2, backend::avx512, backend::neon};
// The vector backends, each tested against the scalar renderer (or skipped
// with the reason where this machine cannot run it).
inline constexpr backend simd_backends[] = {backend::sse2, backend::avx2, backend::avx512,
                                            backend::neon};

std::string_view to_string(backend b);
std::string_view to_string(precision p);
std::optional<backend> parse_backend(std::string_view name);
std::optional<precision> parse_precision(std::string_view name);

// The precision used when none is asked for.
inline constexpr precision default_precision = precision::exact;

// Why this machine cannot run the backend, or nullopt when it can.
std::optional<std::string> backend_unavailable(backend b);
// What `automatic` resolves to on this machine.
backend best_backend();

struct render_options {
  backend which = backend::automatic;
  precision prec = default_precision;
  int threads = 0;  // 0: one per available core
  // What the SIMD kernels may leave out when the scene does not need it (the
  // omit_* flags below). Every combination is bit-identical in exact mode;
  // omit_nothing runs the general path, for tests and the benchmark.
  unsigned omit = ~0u;
};

// The omissions, each tested bit-identical to the general path and timed by
// raycast-bench's special/ rows.
inline constexpr unsigned omit_nothing = 0;
inline constexpr unsigned omit_lanes = 1;     // lesson camera: no x/z lanes, y and z per row
inline constexpr unsigned omit_channels = 2;  // a channel whose two sky colours are equal
inline constexpr unsigned omit_clamps = 4;    // the lerp's select and clamps when provably no-ops
inline constexpr unsigned omit_mirrored = 8;  // lesson camera: mirrored pixels reuse their twin's |d|

struct unsupported_backend : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class renderer {
 public:
  // Throws unsupported_backend when the CPU cannot run the requested backend.
  renderer(const scene& s, const render_options& opts);
  renderer(const renderer&) = delete;  // args_ points into the tables
  renderer& operator=(const renderer&) = delete;

  backend selected() const { return which_; }
  precision prec() const { return prec_; }
  int threads() const { return threads_; }
  const scene& scene_ref() const { return scene_; }

  // Fills the band's rows (any subset of the image), the same bytes whatever
  // the thread count.
  void render(const image_band& band) const;

 private:
  void render_rows(const image_band& band, int64_t r0, int64_t r1, bool paired) const;

  scene scene_;
  float_scene fscene_;
  kernels::kernel_args args_;
  kernels::render_rows_fn kernel_ = nullptr;
  struct free_deleter {
    void operator()(float* p) const;
  };
  using aligned_floats = std::unique_ptr<float[], free_deleter>;
  aligned_floats col_[3], col_x2_;  // per-column tables behind args_, 64-byte aligned
  backend which_;
  precision prec_;
  int threads_;
};

// Number of threads "all cores" means here.
int available_cores();

}  // namespace raycast
