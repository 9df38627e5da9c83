#include "cloud.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace raycast_test {
using namespace raycast;
namespace {

constexpr double near_depth = 2.0, far_depth = 12.0, vfov_degrees = 50.0;
constexpr int64_t width = 1920, height = 1080;

// The viewport at distance 1: vh = 2 tan(vfov / 2), vw = vh * 16 / 9.
double view_height() { return 2.0 * std::tan(vfov_degrees * std::numbers::pi / 360.0); }
double view_width() { return view_height() * double(width) / double(height); }

// Appends x as the JSON writes it: the centres fixed with 6 decimals, the
// radius with 5 significant digits.
void append(std::string& out, double x, bool radius) {
  char buf[40];
  const auto r = radius ? std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific, 4)
                        : std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed, 6);
  out.append(buf, r.ptr);
}

}  // namespace

// A sphere at depth d covers pi r^2 / d^2 of the viewport at distance 1
// (vw * vh): small spheres, ignoring the frame's edges and overlaps. With
// centres uniform in the frustum's volume the depth's density is 3 d^2 /
// (b^3 - a^3) on [a, b], so E[1 / d^2] = 3 (b - a) / (b^3 - a^3), and the
// expected coverage n pi r^2 E[1 / d^2] / (vw vh) is `coverage` when
//   r = sqrt(coverage vw vh (b^3 - a^3) / (3 pi (b - a) n))   (about 6.5 / sqrt(n)).
double cloud_radius(int64_t n, double coverage) {
  const double a = near_depth, b = far_depth;
  const double r = std::sqrt(coverage * view_width() * view_height() * (b * b * b - a * a * a) /
                             (3.0 * std::numbers::pi * (b - a) * double(n)));
  std::string text;
  append(text, r, true);
  double rounded = r;
  std::from_chars(text.data(), text.data() + text.size(), rounded);
  return rounded;
}

api::scene particle_cloud(int64_t n, double coverage) {
  api::scene p;
  p.cam.width = width;
  p.cam.height = height;
  p.cam.vfov = vfov_degrees;
  std::mt19937 gen(20261122u);
  // [0, 1) from the top 24 bits of one word: exact in float and double.
  auto unit = [&gen] { return double(gen() >> 8) * 0x1p-24; };
  auto micro = [](double x) { return std::round(x * 1e6) / 1e6; };
  const double a3 = near_depth * near_depth * near_depth, b3 = far_depth * far_depth * far_depth;
  const double hw = 0.5 * view_width(), hh = 0.5 * view_height(), r = cloud_radius(n, coverage);
  p.spheres.resize(size_t(n));
  for (sphere& s : p.spheres) {
    const double d = std::cbrt(a3 + unit() * (b3 - a3));
    const double x = (2.0 * unit() - 1.0) * hw * d;
    const double y = (2.0 * unit() - 1.0) * hh * d;
    s.center = point3(micro(x), micro(y), micro(-d));
    s.radius = r;
  }
  return p;
}

namespace {

// The packed box's camera (particle_box) and room for its n spheres; and
// their radius: n equal spheres filling 0.3 of the unit cube, exact or
// rounded as the JSON writes it.
api::scene box_view(int64_t n, bool orthographic) {
  api::scene p;
  p.cam.width = width;
  p.cam.height = height;
  if (orthographic) {
    p.cam.projection = projection::orthographic;
    p.cam.viewport_height = 1.2;
    p.cam.lookfrom = point3(0.5, 0.5, 2.0);
  } else {
    p.cam.vfov = 30.0;
    // Far enough that the cube's bounding sphere (radius sqrt(3) / 2) fills the lens's height.
    const double distance = 0.5 * std::sqrt(3.0) / std::sin(15.0 * std::numbers::pi / 180.0);
    const double out = std::round((0.5 + distance / std::sqrt(3.0)) * 1e6) / 1e6;  // as the JSON writes it
    p.cam.lookfrom = point3(out, out, out);
  }
  p.cam.lookat = point3(0.5, 0.5, 0.5);
  p.spheres.resize(size_t(n));
  return p;
}
double exact_box_radius(int64_t n) { return std::cbrt(0.3 * 3.0 / (4.0 * std::numbers::pi * double(n))); }
double box_radius(int64_t n) {
  std::string text;
  append(text, exact_box_radius(n), true);
  double radius = 0;
  std::from_chars(text.data(), text.data() + text.size(), radius);
  return radius;
}

}  // namespace

api::scene particle_box(int64_t n, bool orthographic) {
  api::scene p = box_view(n, orthographic);
  int64_t m = 1;
  while (m * m * m < n) ++m;
  const double cell = 1.0 / double(m);
  const double r = exact_box_radius(n);
  const double room = std::max(0.0, 0.5 * cell - r);  // how far a centre may stray in its cell
  std::mt19937 gen(20261125u);
  auto unit = [&gen] { return double(gen() >> 8) * 0x1p-24; };
  auto micro = [](double x) { return std::round(x * 1e6) / 1e6; };
  // A fixed shuffle of the cells (Fisher-Yates on the generator's words), the first n kept.
  std::vector<int64_t> cells(size_t(m * m * m));
  for (size_t k = 0; k < cells.size(); ++k) cells[k] = int64_t(k);
  for (size_t k = cells.size() - 1; k > 0; --k) std::swap(cells[k], cells[size_t(gen()) % (k + 1)]);
  const double radius = box_radius(n);
  for (size_t k = 0; k < size_t(n); ++k) {
    const int64_t c = cells[k], x = c % m, y = c / m % m, z = c / (m * m);
    sphere& s = p.spheres[k];
    s.center = point3(micro((double(x) + 0.5) * cell + (2.0 * unit() - 1.0) * room),
                      micro((double(y) + 0.5) * cell + (2.0 * unit() - 1.0) * room),
                      micro((double(z) + 0.5) * cell + (2.0 * unit() - 1.0) * room));
    s.radius = radius;
  }
  return p;
}

api::scene particle_box_random(int64_t n) {
  api::scene p = box_view(n, false);
  const double radius = box_radius(n), span = 1.0 - 2.0 * radius;
  std::mt19937 gen(20261129u);
  auto unit = [&gen] { return double(gen() >> 8) * 0x1p-24; };
  auto micro = [](double x) { return std::round(x * 1e6) / 1e6; };
  for (sphere& s : p.spheres) {
    const double x = radius + unit() * span, y = radius + unit() * span, z = radius + unit() * span;
    s.center = point3(micro(x), micro(y), micro(z));
    s.radius = radius;
  }
  return p;
}

namespace {
// `, "name": [x, y, z]` onto out.
void vector_of(std::string& out, const char* name, const vec3& v) {
  out += std::string(", \"") + name + "\": [";
  for (int c = 0; c < 3; ++c) {
    if (c) out += ", ";
    append(out, v[c], false);
  }
  out += "]";
}
}  // namespace

std::string cloud_json(const api::scene& p) {
  std::string out = "{\"camera\": {\"width\": " + std::to_string(p.cam.width) +
                    ", \"height\": " + std::to_string(p.cam.height.value_or(0));
  if (p.cam.projection == projection::orthographic)
    out += ", \"projection\": \"orthographic\", \"viewport_height\": " + std::to_string(p.cam.viewport_height);
  else
    out += ", \"vfov\": " + std::to_string(p.cam.vfov.value_or(90.0));
  if (p.cam.lookat) {
    vector_of(out, "lookfrom", to_glm(p.cam.lookfrom));
    vector_of(out, "lookat", to_glm(*p.cam.lookat));
  }
  out += "},\n \"spheres\": [";
  out.reserve(out.size() + p.spheres.size() * 90 + 8);
  for (size_t k = 0; k < p.spheres.size(); ++k) {
    const sphere& s = p.spheres[k];
    out += k ? ",\n  {\"center\": [" : "\n  {\"center\": [";
    for (int c = 0; c < 3; ++c) {
      if (c) out += ", ";
      append(out, s.center[c], false);
    }
    out += "], \"radius\": ";
    append(out, s.radius, true);
    const char* shade = s.shade == shading::lit ? "lit" : s.shade == shading::flat ? "flat" : "normal";
    out += std::string(", \"shade\": \"") + shade + "\"";
    if (s.shade != shading::normal) vector_of(out, "color", to_glm(s.color));
    out += "}";
  }
  return out + "]}\n";
}

}  // namespace raycast_test
