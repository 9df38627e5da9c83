#include "formats/xyz/extxyz.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include "formats/input/fields.h"
#include "formats/input/table.h"
#include "formats/input/text_trajectory.h"
#include "formats/xyz/comment.h"

namespace raycast::formats {
namespace {

using input::fail_at;
using input::line_cursor;
using xyz::property_spec;

struct xyz_header {
  uint64_t atoms = 0;
  std::vector<property_spec> specs;
  bool plain = false;  // no Properties: species x y z, then anything
  std::optional<particle_cell> cell;
  std::optional<int64_t> timestep;
  uint64_t comment_line = 0;
};

// Three or nine numbers of a value (Lattice, Origin), or nullopt.
std::optional<std::vector<double>> numbers(const std::string& v, size_t n) {
  std::vector<double> out;
  input::fields f(v);
  for (std::string_view w; f.next(w);) {
    const auto x = input::parse_double(w);
    if (!x || !std::isfinite(*x)) return std::nullopt;
    out.push_back(*x);
  }
  if (out.size() != n) return std::nullopt;
  return out;
}

bool flag(std::string_view w, bool& out) {
  if (w == "T" || w == "True" || w == "true" || w == "t") return out = true, true;
  if (w == "F" || w == "False" || w == "false" || w == "f") return out = false, true;
  return false;
}

void cell_of(const xyz::key_values& kv, xyz_header& h, size_t k) {
  const std::string* lattice = xyz::find_key(kv, "Lattice");
  if (!lattice) return;
  const auto l = numbers(*lattice, 9);
  if (!l) fail_at(k, h.comment_line, "Lattice is not nine finite numbers");
  particle_cell c;
  c.a = {(*l)[0], (*l)[1], (*l)[2]};
  c.b = {(*l)[3], (*l)[4], (*l)[5]};
  c.c = {(*l)[6], (*l)[7], (*l)[8]};
  c.periodic = {true, true, true};
  if (const std::string* o = xyz::find_key(kv, "Origin")) {
    const auto v = numbers(*o, 3);
    if (!v) fail_at(k, h.comment_line, "Origin is not three finite numbers");
    c.origin = {(*v)[0], (*v)[1], (*v)[2]};
  }
  if (const std::string* pbc = xyz::find_key(kv, "pbc")) {
    input::fields f(*pbc);
    size_t d = 0;
    for (std::string_view w; f.next(w); ++d)
      if (d >= 3 || !flag(w, c.periodic[d])) fail_at(k, h.comment_line, "pbc is not three of T and F");
    if (d != 3) fail_at(k, h.comment_line, "pbc is not three of T and F");
  }
  h.cell = c;
}

xyz_header read_xyz_header(line_cursor& c, size_t k) {
  xyz_header h;
  std::string_view line;
  if (!c.next(line)) fail_at(k, c.line() + 1, "the file ends where a frame should begin");
  input::fields count(line);
  std::string_view n;
  count.next(n);
  const auto atoms = input::parse_int<uint64_t>(n);
  if (!atoms || !count.done()) fail_at(k, c.line(), "the atom count is not a whole number: " + input::quoted(line));
  h.atoms = *atoms;
  if (!c.next(line)) fail_at(k, c.line() + 1, "the file ends before the comment line");
  h.comment_line = c.line();
  const auto kv = xyz::parse_key_values(line);
  const std::string* props = kv ? xyz::find_key(*kv, "Properties") : nullptr;
  if (!props) {
    h.plain = true;
    h.specs = {{"species", 'S', 1}, {"pos", 'R', 3}};
  } else {
    xyz::specs_result r = xyz::parse_properties(*props);
    if (!r.error.empty()) fail_at(k, h.comment_line, r.error);
    h.specs = std::move(r.specs);
  }
  if (kv) {
    cell_of(*kv, h, k);
    for (const char* key : {"step", "timestep", "Timestep"})
      if (const std::string* s = xyz::find_key(*kv, key))
        if (auto v = input::parse_int<int64_t>(*s)) h.timestep = *v;
  }
  return h;
}

enum class role : uint8_t { skip, number, logical, species };
struct field_plan {
  role what = role::skip;
  uint32_t slot = 0;
  bool checked = false;  // a position or radius: must be finite
  const std::string* name = nullptr;
};

struct xyz_plan {
  std::vector<field_plan> fields;
  std::vector<std::pair<std::string, std::pair<size_t, int>>> properties;  // name, (first slot, components)
  bool radius = false, typed = false;
  size_t slots = 3;
};

xyz_plan plan_fields(const xyz_header& h, const wanted_columns& wanted, size_t k) {
  xyz_plan p;
  bool pos = false;
  for (const property_spec& s : h.specs) {
    if (s.name == "pos" && (s.type != 'R' || s.count != 3)) fail_at(k, h.comment_line, "pos is not R:3");
    if (s.name == "pos") pos = true;
  }
  if (!pos) fail_at(k, h.comment_line, "Properties has no pos (the positions)");
  const auto* radius = [&]() -> const property_spec* {
    for (const property_spec& s : h.specs)
      if ((s.name == "radius" || s.name == "radii") && s.type == 'R' && s.count == 1) return &s;
    return nullptr;
  }();
  if (radius) p.radius = true, p.slots = 4;
  for (const property_spec& s : h.specs) {
    for (uint32_t c = 0; c < s.count; ++c) {
      field_plan f{role::skip, 0, false, &s.name};
      if (s.name == "pos") f = {role::number, c, true, &s.name};
      else if (&s == radius) f = {role::number, 3, true, &s.name};
      else if (s.name == "species" && s.type == 'S' && s.count == 1) f.what = role::species, p.typed = true;
      else if (s.type != 'S' && wanted.wants(s.name)) {
        if (c == 0) p.properties.push_back({s.name, {p.slots, int(s.count)}});
        f = {s.type == 'L' ? role::logical : role::number, uint32_t(p.slots++), false, &s.name};
      }
      p.fields.push_back(f);
    }
  }
  return p;
}

class xyz_trajectory final : public input::text_trajectory {
 public:
  using text_trajectory::text_trajectory;

 private:
  uint64_t read_header(line_cursor& c, size_t k) override {
    header_ = read_xyz_header(c, k);
    size_t fields = 0;
    for (const property_spec& s : header_.specs) fields += s.count;
    room_ = capacity(header_.atoms, 2 * fields);
    return header_.atoms;
  }
  particle_frame read_rows(line_cursor& c, size_t k, uint64_t rows, const wanted_columns& wanted) override;
  void parse_row(std::string_view line, const xyz_plan& p, input::table& t, size_t r, uint64_t no, size_t k);

  xyz_header header_;
  uint64_t room_ = 0;  // the rows the rest of the file can hold
  std::vector<std::string> species_;
  std::optional<input::type_namer> namer_;
};

void xyz_trajectory::parse_row(std::string_view line, const xyz_plan& p, input::table& t, size_t r, uint64_t no,
                               size_t k) {
  input::fields f(line);
  std::string_view w;
  for (size_t j = 0; j < p.fields.size(); ++j) {
    if (!f.next(w)) fail_at(k, no, "the row has " + std::to_string(j) + " values; " + std::to_string(p.fields.size()) +
                                        " expected");
    const field_plan& fp = p.fields[j];
    if (fp.what == role::species) {
      t.types[r] = namer_->index(w);
    } else if (fp.what == role::number) {
      double fast = 0;  // the common decimal, always finite; else any number
      if (input::parse_decimal_padded(w.data(), w.data() + w.size(), fast)) {
        t.slot(fp.slot)[r] = fast;
        continue;
      }
      const auto v = input::parse_double(w);
      if (!v) fail_at(k, no, *fp.name + " is not a number: " + input::quoted(w));
      if (fp.checked && !std::isfinite(*v)) fail_at(k, no, *fp.name + " is not finite: " + input::quoted(w));
      t.slot(fp.slot)[r] = *v;
    } else if (fp.what == role::logical) {
      bool b = false;
      if (!flag(w, b)) fail_at(k, no, *fp.name + " is not T or F: " + input::quoted(w));
      t.slot(fp.slot)[r] = b ? 1.0 : 0.0;
    }
  }
  if (!header_.plain && !f.done())
    fail_at(k, no, "the row has more values than the " + std::to_string(p.fields.size()) + " Properties names");
}

particle_frame xyz_trajectory::read_rows(line_cursor& c, size_t k, uint64_t rows, const wanted_columns& wanted) {
  const xyz_plan plan = plan_fields(header_, wanted, k);
  auto t = std::make_shared<input::table>(size_t(room_), plan.slots, plan.typed);
  species_.clear();
  namer_.emplace(species_);
  std::string_view line;
  for (size_t r = 0; r < rows; ++r) {
    if (r == room_)
      fail_at(k, c.line() + 1, "the header promises " + std::to_string(rows) +
                                   " atoms; the rest of the file can hold at most " + std::to_string(r));
    if (!c.next(line))
      fail_at(k, c.line() + 1, "the header promises " + std::to_string(rows) + " atoms; the file ends after " +
                                   std::to_string(r));
    parse_row(line, plan, *t, r, c.line(), k);
  }
  particle_frame f = input::frame_of(t);
  if (plan.radius) f.radii = t->column(3);
  if (plan.typed) f.type_names = species_;
  for (const auto& [name, at] : plan.properties) f.properties.push_back({name, t->column(at.first), at.second});
  f.cell = header_.cell;
  f.timestep = header_.timestep;
  return f;
}

constexpr std::string_view xyz_extensions[] = {".xyz", ".xyz.gz", ".extxyz", ".extxyz.gz"};

}  // namespace

std::unique_ptr<trajectory> open_xyz(std::unique_ptr<input::text_source> text) {
  return std::make_unique<xyz_trajectory>(std::move(text));
}

const format& xyz_format() {
  static const format f{"extxyz", xyz_extensions, nullptr,
                        [](const std::string& path) { return open_xyz(input::open_text(path)); }};
  return f;
}

}  // namespace raycast::formats
