// The one entry point for rendering: pick a backend, prepare the scene once,
// then fill bands of rows on as many threads as asked.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "float_scene.h"
#include "image.h"
#include "scalar.h"
#include "scene.h"

namespace raycast {

enum class backend : uint8_t {
  automatic,  // the best one this CPU runs
  reference,  // double, the oracle (reference.h)
  scalar,     // float, one pixel at a time (scalar.h)
};

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
};

struct unsupported_backend : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class renderer {
 public:
  // Throws unsupported_backend when the CPU cannot run the requested backend.
  renderer(const scene& s, const render_options& opts);

  backend selected() const { return which_; }
  precision prec() const { return prec_; }
  int threads() const { return threads_; }
  const scene& scene_ref() const { return scene_; }

  // Fills the band's rows (any subset of the image), the same bytes whatever
  // the thread count.
  void render(const image_band& band) const;

 private:
  void render_rows(const image_band& band, int64_t r0, int64_t r1) const;

  scene scene_;
  float_scene fscene_;
  backend which_;
  precision prec_;
  int threads_;
};

// Number of threads "all cores" means here.
int available_cores();

}  // namespace raycast
