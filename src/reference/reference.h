// The oracle: the lesson's loop in double, exactly SPEC.md. Boring on purpose.
#pragma once
#include "image/image.h"
#include "reference/color.h"
#include "scene/scene.h"

namespace raycast {

// Colour of pixel column i, row j (j = 0 is the bottom row), in double.
color reference_pixel(const scene& s, int64_t i, int64_t j);

// Fills the band's rows; single-threaded.
void render_reference(const scene& s, const image_band& band);

}  // namespace raycast
