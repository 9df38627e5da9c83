// Particle data as spheres (particles/spheres.h): each rule of radius,
// colour and shading, the refusals that name the option, and the framing of
// a frame's box (particles/framing.h).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "particles/colormap.h"
#include "particles/elements.h"
#include "particles/framing.h"
#include "particles/spheres.h"

namespace raycast {
namespace {

// Four particles of two types with a column, in arrays of their own.
struct frame_data {
  std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
  std::vector<int32_t> types = {0, 1, 0, 1};
  std::vector<double> pe = {-6, -5, -4, -3};
  particle_frame frame(std::vector<std::string> names = {"1", "2"}) const {
    particle_frame f;
    f.count = 4;
    f.positions = api::packed(xyz.data(), 3);
    f.types = api::packed(types.data());
    f.type_names = std::move(names);
    f.properties.push_back({"c_pe", api::packed(pe.data())});
    return f;
  }
};

std::array<double, 3> colour(const api::sphere_arrays& a, size_t k) {
  return {a.colors.get(k, 0), a.colors.get(k, 1), a.colors.get(k, 2)};
}
std::array<double, 3> as_double(const std::array<float, 3>& c) { return {c[0], c[1], c[2]}; }

TEST(Particles, NumberedTypesTakeThePaletteAndHalfARadius) {
  const frame_data d;
  const particle_spheres s = spheres_of(d.frame(), {});
  EXPECT_EQ(s.arrays.count, 4u);
  EXPECT_EQ(s.arrays.shade, api::shading::lit);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(s.arrays.radii.get(k), 0.5);
    EXPECT_EQ(colour(s.arrays, k), as_double(palette_color(size_t(d.types[k]))));
  }
  EXPECT_EQ(s.arrays.at(3).center, api::vec3(1, 1, 1));
}

TEST(Particles, ElementsTakeTheirRadiusAndColour) {
  const frame_data d;
  const particle_spheres s = spheres_of(d.frame({"Cu", "O"}), {});
  EXPECT_EQ(s.arrays.radii.get(0), double(element_named("Cu")->radius));
  EXPECT_EQ(colour(s.arrays, 1), as_double(element_named("O")->color));
  EXPECT_EQ(element_named("cu"), element_named("Cu"));  // as files spell them
  EXPECT_EQ(element_named("Xx"), nullptr);
  EXPECT_EQ(element_symbol(8), "O");
  // --color-by type: the palette, elements or not.
  api::particles p;
  p.color_by = "type";
  EXPECT_EQ(colour(spheres_of(d.frame({"Cu", "O"}), p).arrays, 1), as_double(palette_color(1)));
}

TEST(Particles, OptionsOverTheDefaults) {
  const frame_data d;
  api::particles p;
  p.type_radius = {{"2", 0.25}};
  p.type_color = {{"1", api::vec3{1, 0, 0}}};
  const particle_spheres s = spheres_of(d.frame(), p);
  EXPECT_EQ(s.arrays.radii.get(0), 0.5);
  EXPECT_EQ(s.arrays.radii.get(1), 0.25);
  EXPECT_EQ(colour(s.arrays, 0), (std::array<double, 3>{1, 0, 0}));
  p.radius = 2.0;  // every sphere's
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(spheres_of(d.frame(), p).arrays.radii.get(k), 2.0);
  p = {};
  p.shade = api::shading::normal;
  EXPECT_EQ(spheres_of(d.frame(), p).arrays.shade, api::shading::normal);
}

TEST(Particles, AColumnThroughTheColormapOverValuesOrPercentiles) {
  const frame_data d;
  api::particles p;
  p.color_by = "c_pe";
  p.colormap = "coolwarm";
  const particle_spheres s = spheres_of(d.frame(), p);
  EXPECT_EQ(colour(s.arrays, 0), as_double(colormap_color(colormap::coolwarm, -6, -6, -3)));
  EXPECT_EQ(colour(s.arrays, 3), as_double(colormap_color(colormap::coolwarm, -3, -6, -3)));
  EXPECT_TRUE(s.note.empty());
  p.color_range = std::array<double, 2>{0, 100};
  p.range_in_percentiles = true;  // numpy's linear percentiles: the min and max
  EXPECT_EQ(colour(spheres_of(d.frame(), p).arrays, 2), colour(s.arrays, 2));
  p.color_range = std::array<double, 2>{50, 100};  // p50 = -4.5
  EXPECT_EQ(colour(spheres_of(d.frame(), p).arrays, 1), as_double(colormap_color(colormap::coolwarm, -5, -4.5, -3)));
  p = {};
  p.color_by = "z";  // a position's coordinate
  EXPECT_EQ(colour(spheres_of(d.frame(), p).arrays, 3), as_double(colormap_color(colormap::viridis, 1, 0, 1)));
}

TEST(Particles, AConstantColumnIsSaid) {
  frame_data d;
  d.pe = {-6.7, -6.7, -6.7, -6.7};
  api::particles p;
  p.color_by = "c_pe";
  const particle_spheres s = spheres_of(d.frame(), p);
  EXPECT_NE(s.note.find("c_pe is -6.7 for every particle of this frame"), std::string::npos) << s.note;
  EXPECT_EQ(colour(s.arrays, 0), as_double(colormap_color(colormap::viridis, 0, 0, 0)));  // the middle
}

TEST(Particles, RefusalsNameTheOption) {
  frame_data d;
  const auto refused = [&](const api::particles& p, particle_frame f) {
    try {
      spheres_of(f, p);
    } catch (const particle_refusal& e) {
      return std::pair<std::string, std::string>{e.keyword, e.what()};
    }
    return std::pair<std::string, std::string>{};
  };
  api::particles p;
  p.color_by = "c_p";
  auto r = refused(p, d.frame());
  EXPECT_EQ(r.first, "color_by");
  EXPECT_NE(r.second.find("did you mean c_pe?"), std::string::npos) << r.second;
  p = {};
  p.type_color = {{"3", api::vec3{0, 0, 0}}};
  r = refused(p, d.frame());
  EXPECT_EQ(r.first, "type_color");
  EXPECT_NE(r.second.find("its types: 1, 2"), std::string::npos) << r.second;
  p = {};
  p.color_by = "element";
  EXPECT_EQ(refused(p, d.frame()).first, "color_by");  // 1 and 2 are no elements
  d.pe[2] = NAN;
  p.color_by = "c_pe";
  r = refused(p, d.frame());
  EXPECT_NE(r.second.find("particle 2's c_pe is nan"), std::string::npos) << r.second;
  particle_frame bare = d.frame();  // no types, no radii
  bare.types.reset();
  bare.type_names.clear();
  EXPECT_EQ(refused({}, bare).first, "radius");
}

TEST(Particles, TheFramedCameraHoldsEveryCorner) {
  frame_data d;
  particle_frame f = d.frame();
  f.cell = particle_cell{{-2, -1, 0}, {4, 0, 0}, {0, 2, 0}, {0, 0, 3}, {}};
  for (const char* view : {"corner", "x", "y", "z"}) {
    const framed_camera c = frame_camera(f, 0.5, view, api::projection::perspective, 35.0, 16.0 / 9.0);
    EXPECT_EQ(c.lookat, api::vec3(0, 0, 1.5)) << view;  // the cell's centre
    // Each corner within the view's half angles.
    const double tv = std::tan(35.0 * M_PI / 360.0);
    for (int k = 0; k < 8; ++k) {
      const double p[3] = {-2.0 + 4 * (k & 1), -1.0 + 2 * ((k >> 1) & 1), 3.0 * (k >> 2)};
      double w[3], dist = 0;
      for (int i = 0; i < 3; ++i) w[i] = c.lookat[size_t(i)] - c.lookfrom[size_t(i)], dist += w[i] * w[i];
      dist = std::sqrt(dist);
      double along = 0, off2 = 0;
      for (int i = 0; i < 3; ++i) along += (p[i] - c.lookfrom[size_t(i)]) * w[i] / dist;
      for (int i = 0; i < 3; ++i) {
        const double o = (p[i] - c.lookfrom[size_t(i)]) - along * w[i] / dist;
        off2 += o * o;
      }
      EXPECT_GT(along, 0.0) << view;
      EXPECT_LT(std::sqrt(off2) / along, tv * 16.0 / 9.0) << view << " corner " << k;
    }
  }
}

}  // namespace
}  // namespace raycast
