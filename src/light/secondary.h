// The secondary rays of lit hits (scene/light.h): the shadow ray toward a
// directional light and the ambient-occlusion rays, one batch of a kernel's
// lanes at a time. Compiled once, not per instruction set: every backend
// calls the same code, so its verdicts are the same bits on every backend,
// thread count and region. Its rules (light/README.md):
//  - origin: the hit on its own sphere, P = C + r n (n the outward unit
//    normal from the kernel, C and r the sphere's in the light's frame:
//    light/far/bvh.h), so P lies within a few float ulps of |C| + r of the
//    surface at every scale;
//  - its own sphere is skipped for a hit seen from outside: a ray leaving a
//    sphere into its outer hemisphere (n . dir > 0: every shadow ray of a
//    lit point, every AO ray) cannot meet it again. A hit seen from inside
//    its sphere (the camera inside) tests it like any other, and is blocked;
//  - any other sphere blocks the ray where the segment meets its solid
//    ball, a start inside it included: no light passes between touching or
//    overlapping spheres.
#pragma once
#include <cstdint>
#include <memory>

#include "light/far/bvh.h"
#include "light/far/shadow_bins.h"
#include "light/kernels.h"
#include "light/near/near_field.h"
#include "sampling/sampler.h"

namespace raycast {

// What a render's lit spheres need beyond the kernel's N . L (built once
// per render): the far field over every sphere, the near field's lists of
// the spheres the camera sees (light/README.md says how a ray finds its
// blockers), and the kernels of the CPU's widest lanes.
struct secondary_rays {
  const sphere_bvh* bvh = nullptr;
  const near_field* near = nullptr;
  const shadow_bins* bins = nullptr;  // shadow rays in an open scene (else their spheres' shadow lists)
  const light_kernels* kernels = nullptr;
  bvh_view view;               // bvh's
  float light[3] = {0, 0, 0};  // unit, toward the light (shadows)
  bool shadows = false;
  sampling::ao_plan ao;        // ao.count rays a hit; 0: none
  float ao_distance = 0;       // grid units; infinity: unbounded
  // Whether a hit's far rays walk in turns (far_occluded_group): where the
  // hierarchy is too big for the caches, so that their waits overlap.
  bool far_in_turns = false;
};

// The structures a render's secondary rays ask, built for its scene when
// it casts them: the far field over every sphere, the near field (empty
// until the render's rays ask for their spheres' lists), and in an open
// scene light-space bins for the shadow rays (there the far field's nodes
// are built for AO alone). light: unit, toward
// the light (world axes); ao: the render's plan; on `threads` threads; width:
// the kernels' lanes (light/kernels.h; 0: the widest this CPU runs); turns:
// whether far rays walk in turns (secondary_rays::far_in_turns; -1: where
// the hierarchy is bigger than 8 MiB). Neither changes a verdict.
class light_structures {
 public:
  light_structures(const scene& s, const float light[3], const sampling::ao_plan& ao, int threads, int width = 0,
                   int turns = -1);
  const secondary_rays& rays() const { return rays_; }
  const sphere_bvh& bvh() const { return bvh_; }
  const near_field& near() const { return *near_; }
  size_t bytes() const { return bvh_.bytes() + near_->bytes() + (bins_ ? bins_->bytes() : 0); }

 private:
  sphere_bvh bvh_;
  std::unique_ptr<near_field> near_;
  std::unique_ptr<shadow_bins> bins_;
  secondary_rays rays_;
};

// One hit's rays as light_lanes casts them, for tests: the hit on sphere k
// (its index in the scene) at p (light frame) with the unit normal n facing
// the ray (inside: the camera is inside its sphere, n faces in). Bit a of
// ao_blocked: AO ray d[a] (m <= 8) meets a sphere within the AO distance;
// shadow_blocked: the ray toward the light does.
uint32_t ao_blocked(const secondary_rays& r, uint32_t k, const float p[3], const float n[3], bool inside,
                    const float (*d)[3], uint32_t m);
bool shadow_blocked(const secondary_rays& r, uint32_t k, const float p[3], bool inside);

// One batch of a kernel: the lanes that hit a lit sphere, and what each
// lane's light needs.
struct lit_lanes {
  static constexpr int most = 16;
  int64_t i0 = 0, j = 0;  // lane 0's pixel column, and the row (0 at the bottom)
  uint32_t sample = 0;    // the antialiasing sample
  uint32_t lit = 0;       // bit l: lane l hit a lit sphere
  uint32_t inside = 0;    // bit l: its normal faces into its sphere (the camera is inside it)
  uint32_t sphere[most];  // the hit sphere's index in the scene
  float n[3][most];       // the unit normal, facing the ray
  float diffuse[most];    // max(0, N . L), or the headlight's
};

// light[l] = lit_ambient A + lit_diffuse diffuse S for each lit lane l.
void light_lanes(const secondary_rays& r, const lit_lanes& lanes, float light[lit_lanes::most]);

// The cosine-weighted direction of numbers (u1, u2) about the unit normal n
// (light/frame.h's frame): phi = 2 pi u1, (sqrt(u2) cos phi,
// sqrt(u2) sin phi, sqrt(1 - u2)) in (t, b, n).
void ao_direction(const float n[3], float u1, float u2, float dir[3]);
// The same for m numbers, four to a vector, as a hit's rays are made: the
// same float operations lane by lane, so the same bits as ao_direction's.
void ao_directions(const float n[3], const float* u1, const float* u2, uint32_t m, float (*dir)[3]);

// c = cos 2 pi u, s = sin 2 pi u (u in [0, 1)), within 1.5e-7, in float
// operations alone: the same bits on every machine, where the C library's
// sincosf may round differently between its builds (with FMA or without).
void unit_circle(float u, float& c, float& s);

}  // namespace raycast
