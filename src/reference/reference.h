// The oracle: the lesson's loop in double, exactly the formulas of src/scene/README.md. Boring on purpose.
// With spheres, the book's ch. 6 world (reference/hittable.h): the closest hit
// for t in [0, infinity) is shaded 0.5 (N + 1) with N facing the ray, or with
// its flat colour; rays that hit nothing see the sky. Ch. 5's and ch. 6's
// earlier single-sphere formulas give the same picture for the built-in scenes
// (tests/test_spheres.cpp computes them independently and compares).
#pragma once
#include "image/image.h"
#include "reference/color.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast {

// Colour of pixel column i, row j (j = 0 is the bottom row), in double.
// Lit spheres under the scene's light (scene/light.h): shadow and ambient-
// occlusion rays against every sphere, ambient occlusion's numbers from ao
// (null: the default sampler's, seed 0).
color reference_pixel(const scene& s, int64_t i, int64_t j, const sampling::ao_plan* ao = nullptr);

// The book's ch. 7 average over the plan's samples (scene/sampler.h gives
// their offsets xi, eta): u = (i + xi) / (W - 1), v = (j + eta) / (H - 1),
// the colours summed in double and divided by the count.
color reference_pixel_samples(const scene& s, const sampling::sample_plan& plan, int64_t i, int64_t j,
                              const sampling::ao_plan* ao = nullptr);

// Fills the band's pixels (its rows and column window); with samples, each
// the average of its samples. Single-threaded.
void render_reference(const scene& s, const image_band& band, const sampling::sample_plan* samples = nullptr,
                      const sampling::ao_plan* ao = nullptr);

}  // namespace raycast
