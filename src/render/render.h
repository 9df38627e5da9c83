// The one entry point for rendering: pick a backend, prepare the scene and
// plan the shortcuts once, then fill bands of rows on as many threads as asked.
#pragma once
#include <optional>

#include "image/image.h"
#include "prepare/culling.h"
#include "prepare/float_scene.h"
#include "kernels/precision.h"
#include "light/secondary.h"
#include "render/backend.h"
#include "render/plan.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast {

struct render_options {
  backend which = backend::automatic;
  precision prec = default_precision;
  int threads = 0;  // 0: one per available core
  // The shortcuts the plan may take when the scene allows them
  // (render/plan.h); shortcut::none runs the general path, for tests and the
  // benchmark. Every set is bit-identical in exact mode.
  unsigned shortcuts = shortcut::all;
  // Antialiasing (scene/sampler.h): samples per pixel; 1 is the one-sample
  // point, no random numbers at all. The sampler and seed matter only above 1.
  uint32_t samples = 1;
  sampler_kind sampler = default_sampler;
  uint64_t seed = 0;
  // Scenes of this many spheres or more are prepared in the order of their
  // image rows (kernels/float_scene.h); tests lower it to cover that order on
  // small scenes.
  size_t sort_from = sorted_from;
  // Their order from sort_from spheres on (kernels/float_scene.h): rows or
  // depth, chosen from the scene; tests force one to compare them.
  sphere_order order = sphere_order::automatic;
};

// The most samples per pixel a render takes (the per-sample table is 16
// bytes a sample).
inline constexpr uint32_t max_samples = uint32_t(1) << 20;

class renderer {
 public:
  // Throws unsupported_backend when the CPU cannot run the requested backend.
  renderer(const scene& s, const render_options& opts);
  renderer(const renderer&) = delete;  // the plan points at fscene_
  renderer& operator=(const renderer&) = delete;

  backend selected() const { return which_; }
  precision prec() const { return prec_; }
  int threads() const { return threads_; }
  uint32_t samples() const { return samples_ ? samples_->plan().count : 1; }
  const camera& cam() const { return scene_.cam; }
  // Seconds the constructor spent on the structures of shadow and AO rays
  // (light/: the far field's hierarchy; 0 where the scene casts none), and
  // their bytes: the hierarchy's, and the near field's lists gathered so
  // far (renders gather them: light_lists()).
  double light_seconds() const { return light_seconds_; }
  size_t light_bytes() const { return secondary_ ? secondary_->bytes() : 0; }
  size_t light_lists() const { return secondary_ ? secondary_->near().lists() : 0; }
  double light_list_seconds() const { return secondary_ ? secondary_->near().seconds() : 0; }  // of render, every thread's
  size_t light_list_bytes() const { return secondary_ ? secondary_->near().bytes() : 0; }

  // Fills the band's pixels (any rows of the image, and any column window:
  // image_band), the same bytes whatever the thread count, band or window.
  void render(const image_band& band) const;

 private:
  void render_rows(const image_band& band, int64_t r0, int64_t r1, bool paired) const;
  void set_light(const scene& s);

  scene scene_;  // the spheres only for the reference backend
  float_scene fscene_;
  backend which_;
  precision prec_;
  int threads_;
  // At most one of the two kernels: none for the reference backend.
  kernels::sky_rows_fn sky_kernel_ = nullptr;
  kernels::sphere_rows_fn sphere_kernel_ = nullptr;
  std::optional<plan> plan_;  // SIMD backends only
  row_index rows_;            // SIMD backends, scenes with spheres
  std::optional<sampling::sample_table> samples_;  // more than one sample
  // Lit spheres' light (scene/light.h), for the SIMD backends: the
  // directional light's unit direction, and the structures that shadow and
  // ambient-occlusion rays ask, built only when the scene casts them.
  float light_[3] = {0, 0, 0};
  sampling::ao_plan ao_;
  std::optional<light_structures> secondary_;
  double light_seconds_ = 0;
};

// Number of threads "all cores" means here.
int available_cores();

}  // namespace raycast
