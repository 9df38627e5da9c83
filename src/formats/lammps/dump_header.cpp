#include "formats/lammps/dump_header.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "formats/input/fields.h"
#include "formats/input/text_trajectory.h"

namespace raycast::formats::lammps {
namespace {

using input::fail_at;
using input::fields;
using input::line_cursor;

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && input::is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && input::is_blank(s.back())) s.remove_suffix(1);
  return s;
}

// The line after an ITEM: line, which must be there.
std::string_view value_line(line_cursor& c, size_t k, std::string_view item) {
  std::string_view line;
  if (!c.next(line)) fail_at(k, c.line() + 1, "the file ends after ITEM: " + std::string(item));
  return trimmed(line);
}

template <class Int>
Int whole_number(line_cursor& c, size_t k, std::string_view item) {
  const std::string_view v = value_line(c, k, item);
  const auto n = input::parse_int<Int>(v);
  if (!n) fail_at(k, c.line(), "ITEM: " + std::string(item) + " is not a whole number: " + input::quoted(v));
  return *n;
}

// The three bound lines: lo, hi (and a tilt factor for a triclinic box).
void bounds(line_cursor& c, size_t k, bool triclinic, double lo[3], double hi[3], double tilt[3]) {
  for (int d = 0; d < 3; ++d) {
    fields f(value_line(c, k, "BOX BOUNDS"));
    double v[3] = {0, 0, 0};
    const int want = triclinic ? 3 : 2;
    for (int j = 0; j < want; ++j) {
      std::string_view s;
      if (!f.next(s)) fail_at(k, c.line(), "a box bound line needs " + std::to_string(want) + " numbers");
      const auto x = input::parse_double(s);
      if (!x || !std::isfinite(*x)) fail_at(k, c.line(), "box bound " + input::quoted(s) + " is not a finite number");
      v[j] = *x;
    }
    if (!f.done()) fail_at(k, c.line(), "a box bound line has more than " + std::to_string(want) + " numbers");
    lo[d] = v[0];
    hi[d] = v[1];
    tilt[d] = v[2];
  }
}

// ITEM: BOX BOUNDS [xy xz yz] BX BY BZ and its three lines, as a cell. A
// triclinic box's lines are its bounding box; the box itself is
// xlo = xlo_bound - min(0, xy, xz, xy + xz), xhi = xhi_bound - max(0, xy, xz, xy + xz),
// ylo = ylo_bound - min(0, yz), yhi = yhi_bound - max(0, yz), edges
// a = (lx, 0, 0), b = (xy, ly, 0), c = (xz, yz, lz) (LAMMPS's Howto triclinic).
particle_cell box(line_cursor& c, size_t k, std::string_view rest) {
  fields f(rest);
  std::vector<std::string_view> words;
  for (std::string_view w; f.next(w);) words.push_back(w);
  const bool triclinic = words.size() >= 3 && words[0] == "xy" && words[1] == "xz" && words[2] == "yz";
  const size_t flags = triclinic ? 3 : 0;
  particle_cell cell;
  for (size_t d = 0; d < 3; ++d)
    cell.periodic[d] = flags + d < words.size() && words[flags + d] == "pp";
  double lo[3], hi[3], t[3];
  bounds(c, k, triclinic, lo, hi, t);
  const double xy = t[0], xz = t[1], yz = t[2];
  if (triclinic) {
    lo[0] -= std::min({0.0, xy, xz, xy + xz});
    hi[0] -= std::max({0.0, xy, xz, xy + xz});
    lo[1] -= std::min(0.0, yz);
    hi[1] -= std::max(0.0, yz);
  }
  for (int d = 0; d < 3; ++d)
    if (!(hi[d] >= lo[d])) fail_at(k, c.line(), "the box's upper bound lies below its lower bound");
  cell.origin = {lo[0], lo[1], lo[2]};
  cell.a = {hi[0] - lo[0], 0, 0};
  cell.b = {xy, hi[1] - lo[1], 0};
  cell.c = {xz, yz, hi[2] - lo[2]};
  return cell;
}

// The section an ITEM: line names ("NUMBER OF ATOMS") and what follows it on
// the line, for the sections that carry words there (BOX BOUNDS, ATOMS).
bool item(std::string_view line, std::string_view& name) {
  line = trimmed(line);
  if (!line.starts_with("ITEM:")) return false;
  name = trimmed(line.substr(5));
  return true;
}

}  // namespace

dump_header read_dump_header(line_cursor& c, size_t k) {
  dump_header h;
  bool counted = false;
  std::string_view line, name;
  if (!c.next(line)) fail_at(k, c.line() + 1, "the file ends where a frame should begin");
  if (!item(line, name)) fail_at(k, c.line(), "expected an ITEM: line, found " + input::quoted(trimmed(line)));
  for (;;) {
    const std::string section(name);  // the cursor's next line may move the bytes name views
    if (section == "TIMESTEP") {
      h.timestep = whole_number<int64_t>(c, k, section);
    } else if (section == "NUMBER OF ATOMS") {
      h.atoms = whole_number<uint64_t>(c, k, section);
      counted = true;
    } else if (section.starts_with("BOX BOUNDS")) {
      h.box = box(c, k, std::string_view(section).substr(10));
    } else if (section.starts_with("ATOMS") && (section.size() == 5 || input::is_blank(section[5]))) {
      if (!counted) fail_at(k, c.line(), "ITEM: ATOMS comes before ITEM: NUMBER OF ATOMS");
      fields f(std::string_view(section).substr(5));
      for (std::string_view w; f.next(w);) h.columns.emplace_back(w);
      if (h.columns.empty()) fail_at(k, c.line(), "ITEM: ATOMS names no columns");
      h.columns_line = c.line();
      return h;
    } else {  // a section of no concern: its lines up to the next ITEM:
      while (c.peek(line) && !item(line, name)) c.next(line);
    }
    if (!c.next(line)) fail_at(k, c.line() + 1, "the file ends before ITEM: ATOMS");
    if (!item(line, name)) fail_at(k, c.line(), "expected an ITEM: line, found " + input::quoted(trimmed(line)));
  }
}

bool looks_like_dump(std::string_view head) {
  while (!head.empty() && (input::is_blank(head.front()) || head.front() == '\n')) head.remove_prefix(1);
  return head.starts_with("ITEM:");
}

}  // namespace raycast::formats::lammps
