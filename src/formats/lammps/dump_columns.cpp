#include "formats/lammps/dump_columns.h"

#include <array>

namespace raycast::formats::lammps {
namespace {

// The position sets in the order preferred: wrapped into the box (what a
// picture of the box shows), unwrapped, then scaled.
struct position_set {
  std::array<const char*, 3> names;
  bool scaled;
};
constexpr std::array<position_set, 4> position_sets = {{
    {{"x", "y", "z"}, false},
    {{"xu", "yu", "zu"}, false},
    {{"xs", "ys", "zs"}, true},
    {{"xsu", "ysu", "zsu"}, true},
}};

int find(const std::vector<std::string>& names, std::string_view n) {
  for (size_t j = 0; j < names.size(); ++j)
    if (names[j] == n) return int(j);
  return -1;
}

}  // namespace

plan_result plan_columns(const std::vector<std::string>& names, const wanted_columns& wanted) {
  plan_result r;
  dump_plan& p = r.plan;
  p.columns.resize(names.size());
  for (size_t j = 0; j < names.size(); ++j)
    if (find(names, names[j]) != int(j)) {
      r.error = "ITEM: ATOMS names " + names[j] + " twice";
      return r;
    }
  bool found = false;
  for (const position_set& s : position_sets) {
    const int x = find(names, s.names[0]), y = find(names, s.names[1]), z = find(names, s.names[2]);
    if (x < 0 || y < 0 || z < 0) continue;
    const int at[3] = {x, y, z};
    for (uint32_t d = 0; d < 3; ++d) p.columns[size_t(at[d])] = {role::number, d, true, 1.0};
    p.scaled = s.scaled;
    found = true;
    break;
  }
  if (!found) {
    r.error = "no position columns (x y z, xu yu zu, xs ys zs or xsu ysu zsu)";
    return r;
  }
  const int radius = find(names, "radius"), diameter = find(names, "diameter");
  const int size = radius >= 0 ? radius : diameter;
  if (size >= 0) {
    p.columns[size_t(size)] = {role::number, 3, true, size == radius ? 1.0 : 0.5};
    p.radius = true;
    p.slots = 4;
  }
  const int element = find(names, "element"), type = find(names, "type");
  if (element >= 0) p.columns[size_t(element)].what = role::element;
  else if (type >= 0) p.columns[size_t(type)].what = role::type_number;
  p.typed = element >= 0 || type >= 0;
  p.elements = element >= 0;
  for (size_t j = 0; j < names.size(); ++j) {
    if (p.columns[j].what != role::skip || !wanted.wants(names[j]) || names[j] == "element") continue;
    p.columns[j] = {role::number, uint32_t(p.slots++), false, 1.0};
    p.properties.push_back(names[j]);
  }
  return r;
}

}  // namespace raycast::formats::lammps
