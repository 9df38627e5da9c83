// A frame of particle data (scene/particles.h) as spheres, as people colour
// them (api::particles):
//   radius  --radius, else the file's radii, else the type's: --type-radius,
//           else its element's van der Waals radius, else 0.5; particles
//           with neither radii nor types need --radius.
//   colour  --color-by PROPERTY through the colormap over --color-range
//           (values, or percentiles of the frame's), --color-by type (a
//           palette), --color-by element (Jmol's colours); by default the
//           file's colours, else its types' (elements by element, others by
//           the palette); --type-color overrides a type's.
//   shading --shade, else lit where the spheres have colours, else by
//           their normals.
// Positions and the file's radii and colours are read in place; what is
// computed (a radius a type, a colour a particle) is owned by the arrays'
// owner, with the frame's memory: 4 bytes a particle for radii by type, 12
// for colours.
#pragma once
#include <stdexcept>
#include <string>

#include "raycast/description.h"
#include "scene/particles.h"

namespace raycast {

// A request the frame cannot meet, naming the particle option it refuses by
// its keyword ("color_by", "type_color", "radius").
struct particle_refusal : std::runtime_error {
  particle_refusal(std::string key, const std::string& why) : std::runtime_error(why), keyword(std::move(key)) {}
  std::string keyword;
};

struct particle_spheres {
  api::sphere_arrays arrays;
  // Said to whoever watches, not refused: a property that is the same for
  // every particle of the frame (every sphere takes the colormap's middle).
  std::string note;
};

// Throws particle_refusal.
particle_spheres spheres_of(const particle_frame& f, const api::particles& p);

}  // namespace raycast
