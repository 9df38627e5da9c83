// LAMMPS text dumps (`dump atom`, `dump custom`), plain or gzipped: the
// format's header is in dump_header.h, the columns' roles in README.md
// ("LAMMPS dumps"): positions from x y z, else xu yu zu, else xs ys zs, else
// xsu ysu zsu (scaled by the box); types from `element` (symbols) or `type`
// (numbers); radii from `radius` or half of `diameter`; any other column a
// named property.
#pragma once
#include <memory>

#include "formats/format.h"
#include "formats/input/text_source.h"

namespace raycast::formats {

const format& lammps_dump_format();

// A dump's frames from a text source (the tests' and fuzzers' bytes in memory).
std::unique_ptr<trajectory> open_lammps_dump(std::unique_ptr<input::text_source> text);

}  // namespace raycast::formats
