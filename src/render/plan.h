// The plan: what a scene lets the SIMD kernels leave out, decided once per
// render, and the per-column tables that make it possible.
//
// Each way of leaving work out is a *shortcut*. A render may take any set of
// them (render_options::shortcuts); the plan takes those the scene allows.
// Every shortcut, alone and with the others, is bit-identical to taking none
// (tests/test_equivalence.cpp); raycast-bench's shortcuts/ rows time each.
#pragma once
#include <cstdlib>
#include <memory>

#include "prepare/float_scene.h"
#include "kernels/kernel.h"
#include "kernels/precision.h"

namespace raycast {

namespace shortcut {
inline constexpr unsigned none = 0;
inline constexpr unsigned lanes = 1;     // axis-aligned camera: no x/z lanes, y and z per row
inline constexpr unsigned channels = 2;  // a channel whose two sky colours are equal: a constant
inline constexpr unsigned clamps = 4;    // the lerp's select and clamps, when provably no-ops
inline constexpr unsigned mirror = 8;    // with lanes: mirrored pixels reuse their twin's |d|
inline constexpr unsigned all = lanes | channels | clamps | mirror;
}  // namespace shortcut

class plan {
 public:
  // For a SIMD kernel: the shortcuts of `allowed` this scene permits, and their
  // tables. `f` must outlive the plan (the kernel arguments point at it).
  plan(const float_scene& f, precision p, unsigned allowed);
  plan(const plan&) = delete;  // args_ points into the tables
  plan& operator=(const plan&) = delete;

  const kernels::kernel_args& args() const { return args_; }
  // Many samples per pixel: the kernels' sampled path (kernels/kernel.h).
  void set_samples(const sampling::sample_plan* p) { args_.samples = p; }
  // Lit spheres' light (float_spheres.h): both must outlive the plan.
  void set_light(const float* direction, const secondary_rays* secondary) {
    args_.spheres.light = direction;
    args_.spheres.secondary = secondary;
    if (secondary) args_.spheres.track_index = true;  // the hit sphere, per lane
  }
  // The frame's row index (kernels/culling.h); it must outlive the plan.
  void set_rows(const row_index& rows) {
    args_.row_first = rows.first.data();
    args_.row_list = rows.list.data();
    args_.row_most = rows.most;
    args_.row_shift = rows.shift;
  }

 private:
  struct free_deleter {
    void operator()(float* p) const { std::free(p); }
  };
  using aligned_floats = std::unique_ptr<float[], free_deleter>;

  kernels::kernel_args args_;
  aligned_floats column_part_[3], column_x2_, ortho_x_;  // 64-byte aligned, behind args_
};

}  // namespace raycast
