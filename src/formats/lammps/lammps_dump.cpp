#include "formats/lammps/lammps_dump.h"

#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

#include "formats/input/fields.h"
#include "formats/input/table.h"
#include "formats/input/text_trajectory.h"
#include "formats/lammps/dump_columns.h"
#include "formats/lammps/dump_header.h"

namespace raycast::formats {
namespace {

using input::fail_at;
using input::line_cursor;
using lammps::dump_header;
using lammps::dump_plan;
using lammps::role;

// The largest LAMMPS type number taken: type k's name is "k", so a file's
// type numbers make that many names.
constexpr int64_t max_type = 1 << 16;

// One row's text into the table's row r.
class row_parser {
 public:
  row_parser(const dump_plan& p, const std::vector<std::string>& names, input::table& t, size_t k)
      : plan_(p), names_(names), t_(t), k_(k), namer_(elements_) {
    for (const lammps::column_plan& c : p.columns) to_.push_back(c.what == role::number ? t.slot(c.slot) : nullptr);
  }

  void parse(std::string_view line, size_t r, uint64_t line_no) {
    const char* p = line.data();
    const char* const e = p + line.size();
    const size_t columns = plan_.columns.size();
    for (size_t j = 0; j < columns; ++j) {
      while (p < e && input::is_blank(*p)) ++p;
      if (p == e) fail_at(k_, line_no, "the row has " + std::to_string(j) + " values; ITEM: ATOMS names " +
                                           std::to_string(columns));
      if (double* to = to_[j]) {
        double v;
        if (const char* end = input::parse_decimal_padded(p, e, v)) {  // the common case: finite
          to[r] = v;
          p = end + (end < e ? 1 : 0);  // past the blank it ends at
        } else {
          p = number(p, e, plan_.columns[j], j, r, line_no);
        }
        continue;
      }
      const lammps::column_plan& c = plan_.columns[j];
      const char* b = p;
      while (p < e && !input::is_blank(*p)) ++p;
      if (c.what == role::type_number) type_number(std::string_view(b, size_t(p - b)), r, line_no);
      else if (c.what == role::element) t_.types[r] = namer_.index(std::string_view(b, size_t(p - b)));
    }
    while (p < e && input::is_blank(*p)) ++p;
    if (p != e)
      fail_at(k_, line_no, "the row has more values than the " + std::to_string(plan_.columns.size()) +
                               " ITEM: ATOMS names");
  }

  int64_t largest_type() const { return largest_; }
  std::vector<std::string>& elements() { return elements_; }

 private:
  const char* number(const char* p, const char* e, const lammps::column_plan& c, size_t j, size_t r,
                     uint64_t line_no) {
    double v = 0;
    const char* got = input::parse_number(p, e, v);
    if (!got || (got < e && !input::is_blank(*got))) {
      const char* end = p;
      while (end < e && !input::is_blank(*end)) ++end;
      fail_at(k_, line_no, names_[j] + " is not a number: " + input::quoted(std::string_view(p, size_t(end - p))));
    }
    if (c.checked && !std::isfinite(v))
      fail_at(k_, line_no, names_[j] + " is not finite: " + input::quoted(std::string_view(p, size_t(got - p))));
    t_.slot(c.slot)[r] = v;
    return got;
  }

  void type_number(std::string_view f, size_t r, uint64_t line_no) {
    const auto n = input::parse_int<int64_t>(f);
    if (!n) fail_at(k_, line_no, "type is not a whole number: " + input::quoted(f));
    if (*n < 1 || *n > max_type)
      fail_at(k_, line_no, "type " + std::to_string(*n) + " is not a LAMMPS type (1 to " + std::to_string(max_type) + ")");
    if (*n > largest_) largest_ = *n;
    t_.types[r] = uint32_t(*n - 1);
  }

  const dump_plan& plan_;
  const std::vector<std::string>& names_;
  input::table& t_;
  size_t k_;
  std::vector<std::string> elements_;
  input::type_namer namer_;
  int64_t largest_ = 0;
  std::vector<double*> to_;  // each column's slot, for the numbers
};

// Scaled positions to the box's space: lo + xs a + ys b + zs c.
void unscale(input::table& t, const particle_cell& cell) {
  double* x = t.slot(0);
  double* y = t.slot(1);
  double* z = t.slot(2);
  const api::vec3 o = cell.origin, a = cell.a, b = cell.b, c = cell.c;
  for (size_t r = 0; r < t.rows; ++r) {
    const double s = x[r], u = y[r], w = z[r];
    x[r] = o.x + s * a.x + u * b.x + w * c.x;
    y[r] = o.y + s * a.y + u * b.y + w * c.y;
    z[r] = o.z + s * a.z + u * b.z + w * c.z;
  }
}

class dump_trajectory final : public input::text_trajectory {
 public:
  using text_trajectory::text_trajectory;

 private:
  uint64_t read_header(line_cursor& c, size_t k) override {
    header_ = lammps::read_dump_header(c, k);
    room_ = capacity(header_.atoms, 2 * header_.columns.size());
    return header_.atoms;
  }

  particle_frame read_rows(line_cursor& c, size_t k, uint64_t rows, const wanted_columns& wanted) override;

  dump_header header_;
  uint64_t room_ = 0;  // the rows the rest of the file can hold
};

particle_frame dump_trajectory::read_rows(line_cursor& c, size_t k, uint64_t rows, const wanted_columns& wanted) {
  const lammps::plan_result planned = lammps::plan_columns(header_.columns, wanted);
  if (!planned.error.empty()) fail_at(k, header_.columns_line, planned.error);
  const dump_plan& plan = planned.plan;
  if (plan.scaled && !header_.box) fail_at(k, header_.columns_line, "scaled positions need ITEM: BOX BOUNDS");
  auto t = std::make_shared<input::table>(size_t(room_), plan.slots, plan.typed);
  row_parser parser(plan, header_.columns, *t, k);
  std::string_view line;
  for (size_t r = 0; r < rows; ++r) {
    if (r == room_)
      fail_at(k, c.line() + 1, "the header promises " + std::to_string(rows) +
                                   " atoms; the rest of the file can hold at most " + std::to_string(r));
    if (!c.next(line))
      fail_at(k, c.line() + 1, "the header promises " + std::to_string(rows) + " atoms; the file ends after " +
                                   std::to_string(r));
    parser.parse(line, r, c.line());
  }
  for (const lammps::column_plan& col : plan.columns)  // a diameter column is halved into the radius
    if (col.what == role::number && col.slot == 3 && col.scale != 1.0)
      for (size_t r = 0; r < t->rows; ++r) t->slot(3)[r] *= col.scale;
  if (plan.scaled) unscale(*t, *header_.box);
  particle_frame f = input::frame_of(t);
  if (plan.radius) f.radii = t->column(3);
  if (plan.elements) {
    f.type_names = std::move(parser.elements());
  } else if (plan.typed) {
    for (int64_t n = 1; n <= parser.largest_type(); ++n) f.type_names.push_back(std::to_string(n));
  }
  for (size_t j = 0; j < plan.properties.size(); ++j)
    f.properties.push_back({plan.properties[j], t->column(plan.slots - plan.properties.size() + j), 1});
  f.cell = header_.box;
  f.timestep = header_.timestep;
  return f;
}

bool sniff_dump(std::string_view head) { return lammps::looks_like_dump(head); }

constexpr std::string_view dump_extensions[] = {".lammpstrj", ".lammpstrj.gz", ".dump", ".dump.gz", ".lammps",
                                                ".lammps.gz", ".lammpsdump", ".lammpsdump.gz"};

}  // namespace

std::unique_ptr<trajectory> open_lammps_dump(std::unique_ptr<input::text_source> text) {
  return std::make_unique<dump_trajectory>(std::move(text));
}

const format& lammps_dump_format() {
  static const format f{"lammps-dump", dump_extensions, sniff_dump,
                        [](const std::string& path) { return open_lammps_dump(input::open_text(path)); }};
  return f;
}

}  // namespace raycast::formats
