// XYZ files, single- or multi-frame, plain or extended (ASE's, OVITO's,
// QUIP's), plain or gzipped. A frame is a count line, a comment line, then
// one row a particle:
//
//   3
//   Lattice="4 0 0 0 4 0 0 0 4" Properties=species:S:1:pos:R:3:forces:R:3 pbc="T T T"
//   Cu 0.0 0.0 0.0 0.1 0.2 0.3
//   ...
//
// Properties names the rows' columns (comment.h); without it a row is
// `species x y z` and any further fields are ignored (plain XYZ, whose
// comment is free text). Species are the type names; pos the positions;
// radius (R:1) the radii; every other numeric property is a named property
// of its count of components. Lattice gives the cell (origin 0, or Origin),
// pbc its periodic flags (T T T where Lattice is given without pbc).
#pragma once
#include <memory>

#include "formats/format.h"
#include "formats/input/text_source.h"

namespace raycast::formats {

const format& xyz_format();

// An XYZ file's frames from a text source (the tests' and fuzzers' bytes).
std::unique_ptr<trajectory> open_xyz(std::unique_ptr<input::text_source> text);

}  // namespace raycast::formats
