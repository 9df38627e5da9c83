#include "particles/spheres.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "particles/colormap.h"
#include "particles/elements.h"
#include "text/names.h"
#include "settings/values.h"

namespace raycast {
namespace {

using rgb = std::array<float, 3>;

// What the arrays point at beyond the frame's own memory.
struct owned {
  std::shared_ptr<const void> frame;
  double radius = 0;
  rgb color{};
  std::vector<float> radii, colors;  // one a particle, three a particle
};

// Each type's radius and colour, as the options and the names say.
struct type_style {
  float radius;
  rgb color;
};

std::string type_list(const particle_frame& f) {
  std::string r;
  for (const std::string& n : f.type_names) r += (r.empty() ? "" : ", ") + n;
  return r;
}

// The index of the type a --type-radius or --type-color key names.
size_t type_index(const particle_frame& f, const std::string& key, const char* keyword) {
  for (size_t k = 0; k < f.type_names.size(); ++k)
    if (f.type_names[k] == key) return k;
  std::vector<std::string_view> names(f.type_names.begin(), f.type_names.end());
  throw particle_refusal(keyword, quote_token(key) + " is not a type of this frame (" +
                                      (names.empty() ? std::string("it has no types") : "its types: " + type_list(f)) +
                                      ")" + did_you_mean(key, names));
}

std::vector<type_style> type_styles(const particle_frame& f, const api::particles& p, bool by_palette) {
  std::vector<type_style> t(f.type_names.size());
  for (size_t k = 0; k < t.size(); ++k) {
    const element_style* e = element_named(f.type_names[k]);
    t[k].radius = e ? e->radius : default_type_radius;
    t[k].color = e && !by_palette ? e->color : palette_color(k);
  }
  for (const auto& [name, r] : p.type_radius) t[type_index(f, name, "type_radius")].radius = float(r);
  for (const auto& [name, c] : p.type_color)
    t[type_index(f, name, "type_color")].color = {float(c.x), float(c.y), float(c.z)};
  return t;
}

// Particle k's type index, checked against the names.
size_t type_of(const particle_frame& f, size_t k) {
  const double v = f.types->get(k);
  if (!(v >= 0.0 && v < double(f.type_names.size())))
    throw particle_refusal("color_by", "particle " + std::to_string(k) + "'s type " + number_text(v) +
                                           " has no name (the frame names " + std::to_string(f.type_names.size()) +
                                           " types)");
  return size_t(v);
}

void set_radii(const particle_frame& f, const api::particles& p, const std::vector<type_style>& styles, owned& o,
               api::sphere_arrays& a) {
  if (p.radius) {
    o.radius = *p.radius;
    a.radii = {&o.radius, api::element::f64, 0, 0};
  } else if (f.radii) {
    a.radii = *f.radii;
  } else if (f.types) {
    o.radii.resize(f.count);
    for (size_t k = 0; k < f.count; ++k) o.radii[k] = styles[type_of(f, k)].radius;
    a.radii = api::packed(o.radii.data());
  } else {
    throw particle_refusal("radius", "the file gives no radius and no types: give --radius R (every sphere's)");
  }
}

// The column --color-by names: a property, or a role's (x, y, z, radius).
std::optional<api::column> property_named(const particle_frame& f, const std::string& name) {
  if (name.size() == 1 && name[0] >= 'x' && name[0] <= 'z') {
    api::column c = f.positions;
    c.data = static_cast<const unsigned char*>(c.data) + (name[0] - 'x') * c.component_stride;
    return c;
  }
  if (name == "radius" && f.radii) return *f.radii;
  if (const particle_property* q = f.property(name)) {
    if (q->components != 1)
      throw particle_refusal("color_by", quote_token(name) + " has " + std::to_string(q->components) +
                                             " components a particle; colour by one number a particle");
    return q->values;
  }
  std::vector<std::string_view> names{"type", "element", "x", "y", "z"};
  std::string list = "type, element, x, y, z";
  if (f.radii) names.push_back("radius"), list += ", radius";
  for (const particle_property& q : f.properties) names.push_back(q.name), list += ", " + q.name;
  throw particle_refusal("color_by", quote_token(name) + " is not a column of this frame (it has: " + list + ")" +
                                         did_you_mean(name, names));
}

// The value at percentile q of the finite values (numpy's linear rule).
double percentile(std::vector<double>& v, double q) {
  const double at = q / 100.0 * double(v.size() - 1);
  const size_t lo = size_t(std::floor(at));
  std::nth_element(v.begin(), v.begin() + ptrdiff_t(lo), v.end());
  const double a = v[lo];
  if (lo + 1 >= v.size()) return a;
  const double b = *std::min_element(v.begin() + ptrdiff_t(lo) + 1, v.end());
  return a + (b - a) * (at - double(lo));
}

// The range a property is shown over: the options', in values or
// percentiles, else its finite values' min and max.
std::array<double, 2> shown_range(const api::column& c, size_t n, const api::particles& p) {
  if (p.color_range && !p.range_in_percentiles) return *p.color_range;
  std::vector<double> v;
  v.reserve(n);
  for (size_t k = 0; k < n; ++k) v.push_back(c.get(k));
  if (v.empty()) return {0.0, 0.0};
  if (p.color_range) return {percentile(v, (*p.color_range)[0]), percentile(v, (*p.color_range)[1])};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return {*lo, *hi};
}

void color_by_property(const particle_frame& f, const api::particles& p, owned& o, particle_spheres& s) {
  const api::column c = *property_named(f, p.color_by);
  for (size_t k = 0; k < f.count; ++k)
    if (const double x = c.get(k); !std::isfinite(x))
      throw particle_refusal("color_by", "particle " + std::to_string(k) + "'s " + p.color_by + " is " +
                                             number_text(x) + ": not a finite number, it cannot be coloured");
  const std::array<double, 2> range = shown_range(c, f.count, p);
  if (range[0] == range[1] && f.count > 0)
    s.note = p.color_by + " is " + number_text(range[0]) + " for every particle of this frame: every sphere " +
             "takes the colormap's middle colour (give --color-range LO,HI to fix the range)";
  const colormap m = colormap_named(p.colormap);
  o.colors.resize(3 * f.count);
  for (size_t k = 0; k < f.count; ++k) {
    const rgb col = colormap_color(m, c.get(k), range[0], range[1]);
    std::copy(col.begin(), col.end(), o.colors.begin() + ptrdiff_t(3 * k));
  }
  s.arrays.colors = api::packed(o.colors.data(), 3);
}

void color_by_type(const particle_frame& f, const std::vector<type_style>& styles, owned& o, api::sphere_arrays& a) {
  if (styles.size() == 1) {  // one colour for all
    o.color = styles[0].color;
    a.colors = {o.color.data(), api::element::f32, 0, sizeof(float)};
    return;
  }
  o.colors.resize(3 * f.count);
  for (size_t k = 0; k < f.count; ++k) {
    const rgb& col = styles[type_of(f, k)].color;
    std::copy(col.begin(), col.end(), o.colors.begin() + ptrdiff_t(3 * k));
  }
  a.colors = api::packed(o.colors.data(), 3);
}

// The colours the options ask for (none: normal shading's).
void set_colors(const particle_frame& f, const api::particles& p, const std::vector<type_style>& styles, owned& o,
                particle_spheres& s) {
  const bool by_type = p.color_by == "type" || p.color_by == "element";
  if (by_type && !f.types)
    throw particle_refusal("color_by", "the file gives no types to colour by" +
                                           std::string(f.properties.empty() ? "" : " (colour by a column instead)"));
  if (p.color_by == "element")
    for (const std::string& n : f.type_names)
      if (!element_named(n))
        throw particle_refusal("color_by", "type " + quote_token(n) + " is no element (its types: " + type_list(f) +
                                               "; --color-by type colours them by a palette)");
  if (!p.color_by.empty() && !by_type) return color_by_property(f, p, o, s);
  if (by_type || (!f.colors && f.types)) return color_by_type(f, styles, o, s.arrays);
  if (f.colors) s.arrays.colors = *f.colors;
}

}  // namespace

particle_spheres spheres_of(const particle_frame& f, const api::particles& p) {
  if (!p.type_radius.empty() || !p.type_color.empty())
    if (!f.types) throw particle_refusal(p.type_color.empty() ? "type_radius" : "type_color", "the file gives no types");
  auto o = std::make_shared<owned>();
  o->frame = f.owner;
  particle_spheres s;
  api::sphere_arrays& a = s.arrays;
  a.count = f.count;
  a.centers = f.positions;
  const std::vector<type_style> styles = f.types ? type_styles(f, p, p.color_by == "type") : std::vector<type_style>{};
  set_radii(f, p, styles, *o, a);
  set_colors(f, p, styles, *o, s);
  a.shade = p.shade.value_or(a.colors.data ? api::shading::lit : api::shading::normal);
  if (a.shade != api::shading::normal && !a.colors.data) {  // flat or lit asked of uncoloured particles
    o->color = default_type_color;
    a.colors = {o->color.data(), api::element::f32, 0, sizeof(float)};
  }
  a.owner = std::move(o);
  return s;
}

}  // namespace raycast
