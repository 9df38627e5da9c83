// GSD files of HOOMD-blue's schema ("hoomd"), as HOOMD, gsd.hoomd and
// fresnel's users write them. Of frame k:
//   particles/N         uint32          the count
//   particles/position  float32 N x 3   positions (read in place)
//   particles/typeid    uint32 N        types (read in place), indices into
//   particles/types     int8 T x W      the type names, 0-padded
//   particles/diameter  float32 N       radii: half of each (default 1: 0.5)
//   configuration/box   float32 x 6     Lx Ly Lz xy xz yz: the cell, centred on the origin
//   configuration/step  uint64          the timestep
// and every other particles/ chunk a named property (velocity, charge,
// mass, image, ...). A chunk frame k lacks is frame 0's (a per-particle one
// only while N is frame 0's), else the schema's default, as gsd.hoomd reads.
#pragma once
#include <memory>
#include <string>

#include "formats/format.h"

namespace raycast::formats {

const format& gsd_format();

// A GSD file's frames from bytes in memory (the tests' and fuzzers'), which
// owner keeps alive.
std::unique_ptr<trajectory> open_gsd(const unsigned char* data, uint64_t size, std::shared_ptr<const void> owner);

}  // namespace raycast::formats
