// Particles as simulation data give them: one frame of a trajectory (a
// LAMMPS dump's, an extended XYZ file's, a GSD file's, a PLY file's
// vertices). The formats room's readers fill it (src/formats/); the scene
// turns it into spheres as the user asks (radius and colour by type, element
// or property). Columns are views (raycast/description.h): into the file's
// own memory where its layout allows (GSD's chunks, PLY's body), else into
// arrays the reader decoded; `owner` keeps either alive.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raycast/description.h"

namespace raycast {

// The simulation cell: the parallelepiped origin + s a + t b + u c, s, t, u
// in [0, 1] (an orthogonal box has a, b, c along x, y, z).
struct particle_cell {
  api::vec3 origin, a, b, c;
  std::array<bool, 3> periodic{};
};

// A column the file names that is none of the roles below (LAMMPS's vx,
// c_pe, id; XYZ's forces; GSD's charge): `components` values a row.
struct particle_property {
  std::string name;
  api::column values;
  int components = 1;
};

struct particle_frame {
  size_t count = 0;
  api::column positions;              // count x 3, world units
  std::optional<api::column> radii;   // count (a file's diameters are halved into radii by its reader)
  std::optional<api::column> colors;  // count x 3, in [0, 1] (u8 columns read as value / 255)
  // Each particle's type: a whole number in [0, type_names.size()), and each
  // type's name as the file gives it: an element symbol (XYZ's species, a
  // LAMMPS dump's element column), GSD's type name, or a LAMMPS type number
  // ("1", "2", ...: type k's name is k, its index k - 1).
  std::optional<api::column> types;
  std::vector<std::string> type_names;
  std::vector<particle_property> properties;
  std::optional<particle_cell> cell;
  std::optional<int64_t> timestep;  // the simulation's step, where the file says
  std::shared_ptr<const void> owner;

  const particle_property* property(std::string_view name) const {
    for (const particle_property& p : properties)
      if (p.name == name) return &p;
    return nullptr;
  }
};

}  // namespace raycast
