// The oracle: the lesson's loop in double, exactly the formulas of src/scene/README.md. With
// spheres, the book's ch. 6 world (hittable.h): the closest hit for t in [0, infinity) shaded
// 0.5 (N + 1) with N facing the ray, or its flat or lit colour; a miss sees the sky.
#pragma once
#include "image/image.h"
#include "reference/color.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast {

// Colour of pixel column i, row j (0 at the bottom). Lit spheres under the scene's light: shadow
// and AO rays against every sphere, AO's numbers from ao (null: the default sampler's, seed 0).
color reference_pixel(const scene& s, int64_t i, int64_t j, const sampling::ao_plan* ao = nullptr);

// The book's ch. 7 average over the plan's samples: u = (i + xi) / (W - 1), v = (j + eta) / (H - 1),
// the colours summed in double and divided by the count.
color reference_pixel_samples(const scene& s, const sampling::sample_plan& plan, int64_t i, int64_t j,
                              const sampling::ao_plan* ao = nullptr);

// Fills the band's pixels (its rows and column window), single-threaded.
void render_reference(const scene& s, const image_band& band, const sampling::sample_plan* samples = nullptr,
                      const sampling::ao_plan* ao = nullptr);

}  // namespace raycast
