// The particle readers against files the real tools wrote at test time
// (tests/formats/make_files.sh, CTest's fixture formats.files): LAMMPS's
// dump atom and dump custom (plain and gzipped by LAMMPS, orthogonal and
// triclinic boxes, an atom count that changes), ASE's extended XYZ writer
// and gsd's HOOMD writer, the last two given LAMMPS's frames; and gsd's own
// file of its 1.0 layer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include "formats/gsd/gsd_file.h"
#include "formats/gsd/hoomd.h"
#include "formats/input/mapped_file.h"
#include "formats/lammps/lammps_dump.h"
#include "formats/xyz/extxyz.h"

namespace {

using namespace raycast;
using namespace raycast::formats;

std::string file(const std::string& name) { return std::string(RAYCAST_FORMATS_FILES) + "/" + name; }

std::unique_ptr<trajectory> open(const format& f, const std::string& name) { return f.open(file(name)); }

wanted_columns all() {
  wanted_columns w;
  w.all = true;
  return w;
}

// Rows by the id column (rows may come in any order).
std::map<long, size_t> by_id(const particle_frame& f) {
  std::map<long, size_t> m;
  const particle_property* id = f.property("id");
  EXPECT_NE(id, nullptr);
  for (size_t k = 0; id && k < f.count; ++k) m[long(id->values.get(k))] = k;
  return m;
}

api::vec3 position(const particle_frame& f, size_t k) {
  return {f.positions.get(k, 0), f.positions.get(k, 1), f.positions.get(k, 2)};
}

std::string type_name(const particle_frame& f, size_t k) { return f.type_names.at(size_t(f.types->get(k))); }

TEST(LammpsDump, ScaledAndUnscaledPositionsAgree) {
  for (auto [scaled, plain, tol] : {std::tuple{"melt.atom", "melt.dump", 2e-5}, {"tri.atom", "tri.dump", 2e-5}}) {
    auto a = open(lammps_dump_format(), scaled), b = open(lammps_dump_format(), plain);
    ASSERT_EQ(a->frame_count(), b->frame_count()) << scaled;
    ASSERT_GE(a->frame_count(), 3u);
    for (size_t k = 0; k < a->frame_count(); ++k) {
      const particle_frame fa = a->read(k, all()), fb = b->read(k, all());
      ASSERT_EQ(fa.count, fb.count);
      const auto ia = by_id(fa), ib = by_id(fb);
      for (const auto& [id, ra] : ia) {
        const size_t rb = ib.at(id);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fa.positions.get(ra, c), fb.positions.get(rb, c), tol) << scaled << " id " << id;
        EXPECT_EQ(fa.types->get(ra), fb.types->get(rb));
      }
    }
  }
}

TEST(LammpsDump, GzippedByLammpsAndPlainAgreeExactly) {
  auto plain = open(lammps_dump_format(), "melt.dump"), gz = open(lammps_dump_format(), "melt.dump.gz");
  ASSERT_EQ(plain->frame_count(), gz->frame_count());
  for (size_t k = 0; k < plain->frame_count(); ++k) {
    const particle_frame a = plain->read(k, all()), b = gz->read(k, all());
    ASSERT_EQ(a.count, b.count);
    ASSERT_EQ(a.properties.size(), b.properties.size());
    for (size_t r = 0; r < a.count; ++r) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.positions.get(r, c), b.positions.get(r, c));
      for (size_t p = 0; p < a.properties.size(); ++p) ASSERT_EQ(a.properties[p].values.get(r), b.properties[p].values.get(r));
    }
    EXPECT_EQ(a.timestep, b.timestep);
  }
}

TEST(LammpsDump, TriclinicBoxIsTheOneLammpsStates) {
  std::ifstream in(file("box.txt"));
  double lx, ly, lz, xy, xz, yz, xlo, ylo, zlo;
  ASSERT_TRUE(in >> lx >> ly >> lz >> xy >> xz >> yz >> xlo >> ylo >> zlo);
  ASSERT_NE(xy, 0.0);
  ASSERT_LT(xz, 0.0);
  for (const char* name : {"tri.dump", "tri.atom"}) {
    auto t = open(lammps_dump_format(), name);
    const particle_frame f = t->read(t->frame_count() - 1, {});
    ASSERT_TRUE(f.cell);
    const particle_cell& c = *f.cell;
    const double e = 1e-12 * lx;
    EXPECT_NEAR(c.origin.x, xlo, e);
    EXPECT_NEAR(c.origin.y, ylo, e);
    EXPECT_NEAR(c.origin.z, zlo, e);
    const api::vec3 want[3] = {{lx, 0, 0}, {xy, ly, 0}, {xz, yz, lz}}, got[3] = {c.a, c.b, c.c};
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[v][size_t(d)], want[v][size_t(d)], e) << name << " edge " << v;
    EXPECT_EQ(c.periodic, (std::array<bool, 3>{true, true, true}));
  }
}

TEST(LammpsDump, AtomCountChangesBetweenFramesAndFramesReadInAnyOrder) {
  auto t = open(lammps_dump_format(), "melt.dump");
  std::vector<particle_frame> in_order;
  for (size_t k = 0; k < 5; ++k) in_order.push_back(t->read(k, all()));  // before frame_count: the index grows
  EXPECT_EQ(t->frame_count(), 5u);
  EXPECT_EQ(in_order[0].count, in_order[2].count);
  EXPECT_LT(in_order[3].count, in_order[2].count);  // atoms deleted between the runs
  EXPECT_EQ(in_order[3].count, in_order[4].count);
  auto u = open(lammps_dump_format(), "melt.dump.gz");
  for (size_t k : {4u, 1u, 3u, 0u}) {  // backwards in a .gz starts it again
    const particle_frame f = u->read(k, all());
    ASSERT_EQ(f.count, in_order[k].count);
    EXPECT_EQ(*f.timestep, int64_t(10 * k));
    for (size_t r = 0; r < f.count; ++r) ASSERT_EQ(position(f, r), position(in_order[k], r));
  }
}

TEST(LammpsDump, ColumnsTakeTheirRoles) {
  auto t = open(lammps_dump_format(), "melt.dump");
  const particle_frame f = t->read(1, all());
  std::vector<std::string> names;
  for (const particle_property& p : f.properties) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"id", "xu", "yu", "zu", "vx", "vy", "vz", "c_pe"}));
  EXPECT_EQ(f.type_names, (std::vector<std::string>{"1", "2"}));
  EXPECT_FALSE(f.radii);
  EXPECT_EQ(f.cell->periodic, (std::array<bool, 3>{true, true, false}));  // boundary p p s
  EXPECT_EQ(f.timestep, 10);
  wanted_columns pe;
  pe.properties = {"c_pe"};
  const particle_frame g = t->read(1, pe);
  ASSERT_EQ(g.properties.size(), 1u);
  EXPECT_EQ(g.properties[0].name, "c_pe");
  for (size_t r = 0; r < f.count; ++r) ASSERT_EQ(g.properties[0].values.get(r), f.property("c_pe")->values.get(r));
  auto e = open(lammps_dump_format(), "melt-elements.lammpstrj");
  EXPECT_EQ(e->read(0, {}).type_names, (std::vector<std::string>{"Ar", "Kr"}));
}

TEST(CrossFormat, TheSameFrameFromEachFormatGivesTheSamePositionsTypesAndBox) {
  auto lmp = open(lammps_dump_format(), "melt-elements.lammpstrj");
  auto xyz = open(xyz_format(), "melt.extxyz");
  auto gsd = open(gsd_format(), "melt.gsd");
  ASSERT_EQ(lmp->frame_count(), 5u);
  ASSERT_EQ(xyz->frame_count(), 5u);
  ASSERT_EQ(gsd->frame_count(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    const particle_frame l = lmp->read(k, {}), x = xyz->read(k, {}), g = gsd->read(k, {});
    ASSERT_EQ(l.count, x.count);
    ASSERT_EQ(l.count, g.count);
    EXPECT_EQ(l.timestep, x.timestep);
    EXPECT_EQ(l.timestep, g.timestep);
    const particle_cell &lc = *l.cell, &xc = *x.cell, &gc = *g.cell;
    EXPECT_EQ(lc.origin, xc.origin);
    EXPECT_EQ(lc.periodic, xc.periodic);
    for (auto [a, b, c] : {std::tuple{lc.a, xc.a, gc.a}, {lc.b, xc.b, gc.b}, {lc.c, xc.c, gc.c}})
      for (size_t d = 0; d < 3; ++d) {
        EXPECT_EQ(a[d], b[d]);
        EXPECT_EQ(float(a[d]), float(c[d]));
      }
    for (size_t r = 0; r < l.count; ++r) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(float(l.positions.get(r, c)), float(x.positions.get(r, c))) << "frame " << k << " row " << r;
        // GSD's box is centred on the origin: the same point relative to the box's corner.
        ASSERT_NEAR(l.positions.get(r, c) - lc.origin[size_t(c)], g.positions.get(r, c) - gc.origin[size_t(c)], 1e-5);
      }
      ASSERT_EQ(type_name(l, r), type_name(x, r));
      ASSERT_EQ(type_name(l, r), type_name(g, r));
    }
  }
}

TEST(Gsd, ChunksAFrameLacksAreFrameZerosElseTheSchemasDefaults) {
  auto map = input::mapped_file::open(file("inherit.gsd"));
  const gsd::gsd_file layer(map->data(), map->size(), map);
  ASSERT_EQ(layer.frames(), 3u);
  ASSERT_TRUE(layer.find(1, "particles/position"));
  for (const char* lacking : {"particles/typeid", "particles/types", "particles/diameter", "configuration/box",
                              "particles/velocity", "particles/N"})
    EXPECT_FALSE(layer.find(1, lacking)) << lacking << ": gsd.hoomd wrote what it leaves out";

  auto t = open(gsd_format(), "inherit.gsd");
  const particle_frame f0 = t->read(0, all()), f1 = t->read(1, all()), f2 = t->read(2, all());
  EXPECT_EQ(f1.count, 4u);
  EXPECT_EQ(f1.type_names, (std::vector<std::string>{"A", "B", "C"}));
  const double radii[4] = {0.5, 1.0, 0.25, 1.5};
  const uint32_t types[4] = {0, 2, 1, 2};
  for (size_t r = 0; r < 4; ++r) {
    EXPECT_EQ(f1.radii->get(r), radii[r]);
    EXPECT_EQ(f1.types->get(r), types[r]);
    EXPECT_EQ(f1.positions.get(r, 0), f0.positions.get(r, 0) + 0.5);
    EXPECT_EQ(f1.property("velocity")->values.get(r, 2), f0.property("velocity")->values.get(r, 2));
  }
  EXPECT_EQ(f1.timestep, 200);
  const api::vec3 a{10, 0, 0}, b{6, 12, 0}, c{3.5, -7, 14};
  EXPECT_EQ(f1.cell->a, a);
  EXPECT_EQ(f1.cell->b, b);
  EXPECT_EQ(f1.cell->c, c);
  EXPECT_EQ(f1.cell->origin, (api::vec3{-9.75, -2.5, -7}));
  // Six particles, not frame 0's four: per-particle chunks take the defaults.
  EXPECT_EQ(f2.count, 6u);
  EXPECT_EQ(f2.type_names, f0.type_names);
  for (size_t r = 0; r < 6; ++r) {
    EXPECT_EQ(f2.radii->get(r), 0.5);
    EXPECT_EQ(f2.types->get(r), 0.0);
    EXPECT_EQ(f2.positions.get(r, 1), double(r));
  }
  EXPECT_EQ(f2.property("velocity"), nullptr);
  EXPECT_EQ(f2.cell->a, a);
  // Positions are the file's float32 chunk, viewed in place.
  EXPECT_EQ(f0.positions.type, api::element::f32);
  EXPECT_EQ(f0.positions.stride, 12);
}

TEST(Gsd, ReadsTheVersionOneLayerOfGsdsOwnFile) {
  std::ifstream listing(file("v1_chunks.txt"));
  if (!listing) GTEST_SKIP() << "this gsd package ships no test_gsd_v1.gsd";
  auto map = input::mapped_file::open(file("v1.gsd"));
  const gsd::gsd_file layer(map->data(), map->size(), map);
  size_t frames = 0, chunks = 0;
  uint64_t k = 0;
  std::string name;
  int32_t value = 0;
  while (listing >> k >> name >> value) {
    const auto c = layer.find(size_t(k), name);
    ASSERT_TRUE(c) << "frame " << k << " " << name;
    ASSERT_EQ(c->type, gsd::i32);
    ASSERT_EQ(c->N * c->M, 1u);
    EXPECT_EQ(int32_t(gsd::load_le<uint32_t>(layer.at(c->location))), value) << "frame " << k << " " << name;
    frames = std::max(frames, size_t(k) + 1);
    ++chunks;
  }
  EXPECT_GT(chunks, 100u);
  EXPECT_EQ(layer.frames(), frames);
  EXPECT_FALSE(layer.find(0, "no such chunk"));
}

}  // namespace
