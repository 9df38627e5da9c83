// The ways of computing the sky the bench compares, and their error against
// the double reference, measured band by band so that no full-size extra
// image is ever needed.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "autovec.h"
#include "image/image.h"
#include "render/render.h"
#include "reference_errors.h"
#include "stiff_cases.h"

namespace raycast::bench {

// One way of computing the sky: a core backend at a precision, or the
// autovec peer (which has only `exact`).
struct path {
  std::string backend;  // the row name's BACKEND: reference, scalar, autovec, ...
  raycast::backend core = raycast::backend::reference;  // unused for autovec
  raycast::precision prec = raycast::precision::exact;
  bool autovec = false;

  std::string label() const;  // "backend/precision"
};

// Every path this CPU runs, in the rows' order: reference, scalar, autovec,
// sse2, avx2, avx512; exact before fast.
std::vector<path> available_paths();

struct skipped_backend {
  std::string name, reason;
};
// Backends this CPU cannot run, with raycast::backend_unavailable's reason.
std::vector<skipped_backend> skipped_backends();

// Renders a path's image (any band of rows) with a fixed thread count.
class painter {
 public:
  // shortcuts: render_options::shortcuts for the core backends (the
  // shortcuts/ rows).
  painter(const path& p, const scene& s, int threads, unsigned shortcuts = shortcut::all);
  void render(const image_band& band) const;

 private:
  std::unique_ptr<renderer> core_;
  autovec_camera autovec_;
  int threads_ = 1;
};

// The scenes, cases and error measurement the tests use too (tests/support).
using raycast_test::error_stats;
using raycast_test::make_scene;
using raycast_test::sized;
using raycast_test::stiff_case;
using raycast_test::stiff_cases;

// Each path's error against reference_pixel over the whole image of s
// (tests/support/reference_errors.h); the reference path reports zeros.
// Bands of rows are spread over all cores.
std::vector<error_stats> measure_errors(const scene& s, const std::vector<path>& paths);

// The one output buffer every timed row writes into (bench/errors.cpp): grown
// when a row needs more and touched once, so no timed iteration pays for page faults.
unsigned char* scratch(size_t bytes);

}  // namespace raycast::bench
