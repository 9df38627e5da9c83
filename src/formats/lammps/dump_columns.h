// What each column of a dump's ITEM: ATOMS line becomes: one of the
// positions (the first complete set of x y z, xu yu zu, xs ys zs, xsu ysu
// zsu), the radius (radius, else diameter halved), the type (element's
// symbols, else type's numbers), a property the caller wants, or nothing
// (its text skipped unparsed).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/format.h"

namespace raycast::formats::lammps {

enum class role : uint8_t { skip, number, type_number, element };

struct column_plan {
  role what = role::skip;
  uint32_t slot = 0;      // the table's slot of a number
  bool checked = false;   // a position or radius: must be finite
  double scale = 1.0;     // 0.5 for a diameter
};

struct dump_plan {
  std::vector<column_plan> columns;  // one per ITEM: ATOMS name
  std::vector<std::string> properties;  // the name of slot 3 + radius + k onward (k = 0, 1, ...)
  bool scaled = false;   // positions are fractions of the box's edges
  bool radius = false;   // slot 3 is the radius
  bool typed = false;
  bool elements = false; // the types are element symbols (else LAMMPS type numbers)
  size_t slots = 3;
};

// The plan for these columns, or a message why they cannot give positions.
struct plan_result {
  dump_plan plan;
  std::string error;
};
plan_result plan_columns(const std::vector<std::string>& names, const wanted_columns& wanted);

}  // namespace raycast::formats::lammps
