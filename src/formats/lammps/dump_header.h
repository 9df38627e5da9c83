// A LAMMPS text dump frame's header: the ITEM: sections before its rows.
//
//   ITEM: TIMESTEP
//   1000
//   ITEM: NUMBER OF ATOMS
//   108
//   ITEM: BOX BOUNDS xy xz yz pp pp ff     ("xy xz yz" only for a triclinic box)
//   xlo_bound xhi_bound xy                 (the tilt only for a triclinic box)
//   ylo_bound yhi_bound xz
//   zlo_bound zhi_bound yz
//   ITEM: ATOMS id type xs ys zs           (the rows' columns, any names, any order)
//
// Other sections (dump_modify's ITEM: UNITS, ITEM: TIME) are skipped.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "formats/input/line_cursor.h"
#include "scene/particles.h"

namespace raycast::formats::lammps {

struct dump_header {
  std::optional<int64_t> timestep;
  uint64_t atoms = 0;
  std::optional<particle_cell> box;  // origin (xlo, ylo, zlo) and the edges a, b, c
  std::vector<std::string> columns;  // ITEM: ATOMS's names
  uint64_t columns_line = 0;         // the ITEM: ATOMS line's number
};

// Reads frame k's header, the cursor on its first line; throws format_error
// "frame k (line L): ..." where it is not one.
dump_header read_dump_header(input::line_cursor& c, size_t k);

// Whether a text begins as a dump does: its first line that is not blank is
// an ITEM: line.
bool looks_like_dump(std::string_view head);

}  // namespace raycast::formats::lammps
