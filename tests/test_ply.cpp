// Particle files (--scene FILE.ply, formats/ply.h): the three encodings render
// the bytes of the JSON scene holding the same spheres on every backend;
// --radius and --color-by; and every kind of hostile file refused with the
// part of the file and the byte where it goes wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <bit>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "raycast/raycast.h"
#include "particles/colormap.h"
#include "formats/registry.h"
#include "prepare/float_scene.h"
#include "render/backend.h"
#include "render_support.h"
#include "formats/ply.h"
#include "formats/json.h"
#include "particles.h"

namespace {

using namespace raycast;
using raycast_test::compare;
using raycast_test::difference;
using raycast_test::image;
using raycast_test::render_with;
using namespace raycast_test;

byte_source memory(const std::string& bytes, bool unchanged = true) {
  byte_source src = memory_source(bytes);
  src.unchanged = [unchanged] { return unchanged; };
  return src;
}

api::scene read_ok(const std::string& bytes, const api::particles& o = {}) {
  auto r = read_ply(memory(bytes), o);
  if (auto* e = std::get_if<scene_file_error>(&r)) {
    ADD_FAILURE() << e->path << ": " << e->message;
    return {};
  }
  return std::move(std::get<scene_file_contents>(r).scene);
}

scene_file_error refused(const std::string& bytes, const api::particles& o = {}) {
  auto r = read_ply(memory(bytes), o);
  if (auto* e = std::get_if<scene_file_error>(&r)) return *e;
  ADD_FAILURE() << "read without an error";
  return {};
}

api::camera test_camera() {
  api::camera c;
  c.width = 160;
  c.height = 90;
  c.lookfrom = vec3(0.5, 1.0, 3.0);
  c.lookat = vec3(0.0, 0.0, -5.0);
  c.vfov = 40.0;
  return c;
}

image rendered(api::scene p, backend b, sphere_order order = sphere_order::automatic) {
  p.cam = test_camera();
  EXPECT_FALSE(validate(p));
  render_options o;
  o.which = b;
  o.threads = 2;
  if (order != sphere_order::automatic) {
    o.sort_from = 0;  // reordered however small
    o.order = order;
  }
  return render_with(renderer(make_scene(p), o), pixel_format::rgb8);
}

TEST(Ply, EveryEncodingRendersTheJsonScenesBytesOnEveryBackend) {
  const std::vector<particle> ps = random_particles(3000, 7);
  auto json = parse_scene_file(json_of(ps));
  ASSERT_TRUE(std::holds_alternative<api::scene>(json));
  const api::scene from_json = std::get<api::scene>(json);
  for (backend b : all_backends) {
    if (backend_unavailable(b)) continue;
    const image want = rendered(from_json, b);
    for (enc e : {enc::ascii, enc::little, enc::big}) {
      const std::string bytes = ply_of(ps, e);
      const api::scene p = read_ok(bytes);
      ASSERT_TRUE(p.arrays);
      EXPECT_EQ(p.arrays->count, ps.size());
      const difference d = compare(rendered(p, b), want);
      EXPECT_EQ(d.max, 0) << to_string(b) << " " << format_names[int(e)] << ": " << d.where();
    }
  }
}

// A binary file is read in place: the view's columns point into the body
// with the file's row stride, byte-swapped for big-endian.
// A particle file's spheres are arrays, and the float scene is prepared from
// them in its own order (read out of order, written front to back; a JSON
// scene's the other way): the same bytes as the JSON scene's in the scene's
// order, row order and depth order.
TEST(Ply, EveryOrderOfPreparationGivesTheSameBytes) {
  const std::vector<particle> ps = random_particles(40000, 9);  // two threads' chunks from 2^15 spheres
  const api::scene from_json = std::get<api::scene>(parse_scene_file(json_of(ps)));
  for (enc e : {enc::little, enc::ascii}) {
    api::scene p = read_ok(ply_of(ps, e));
    ASSERT_TRUE(p.arrays);
    for (sphere_order order : {sphere_order::scene, sphere_order::rows, sphere_order::depth}) {
      const difference d =
          compare(rendered(p, backend::automatic, order), rendered(from_json, backend::automatic, order));
      EXPECT_EQ(d.max, 0) << format_names[int(e)] << " order " << int(order) << ": " << d.where();
      EXPECT_EQ(compare(rendered(p, backend::automatic, order), rendered(from_json, backend::automatic)).max, 0);
    }
  }
}

TEST(Ply, BinaryBodiesAreReadInPlace) {
  const std::vector<particle> ps = random_particles(10, 3);
  for (enc e : {enc::little, enc::big}) {
    const api::scene p = read_ok(ply_of(ps, e));
    ASSERT_TRUE(p.arrays);
    EXPECT_EQ(p.arrays->centers.stride, 23);  // x y z radius (16) rgb (3) id (4)
    EXPECT_EQ(p.arrays->centers.component_stride, 4);
    EXPECT_EQ(p.arrays->centers.byte_swapped, e == enc::big);
    EXPECT_EQ(p.arrays->colors.type, api::element::u8);
    EXPECT_TRUE(p.arrays->owner);
    for (size_t k = 0; k < ps.size(); ++k) {
      const sphere s = p.arrays->at(k);
      EXPECT_EQ(s.center, vec3(ps[k].x, ps[k].y, ps[k].z));
      EXPECT_EQ(s.radius, double(ps[k].radius));
      EXPECT_EQ(s.color[1], ps[k].rgb[1] / 255.0);
      EXPECT_EQ(s.shade, shading::lit);
    }
  }
}

// Elements before the vertex element (a mesh's faces, with lists) are
// skipped; without colours the spheres are shaded by their normals.
TEST(Ply, OtherElementsAreSkippedAndNoColoursMeansNormalShading) {
  const std::vector<particle> ps = random_particles(20, 5);
  for (enc e : {enc::ascii, enc::little, enc::big}) {
    std::string faces;
    if (e == enc::ascii) faces = "3 0 1 2\n4 1 2 3 4\n";
    else {
      for (int n : {3, 4}) {
        faces.push_back(char(n));
        for (int k = 0; k < n; ++k) put(faces, int32_t(k), e == enc::big);
      }
    }
    std::string bytes = ply_of(ps, e, true, false, "element face 2\nproperty list uchar int vertex_indices\n");
    const size_t body = bytes.find("end_header\n") + 11;
    bytes.insert(body, faces);
    const api::scene p = read_ok(bytes);
    ASSERT_TRUE(p.arrays);
    EXPECT_EQ(p.arrays->shade, shading::normal);
    EXPECT_FALSE(p.arrays->colors.data);
    EXPECT_EQ(p.arrays->at(19).center, vec3(ps[19].x, ps[19].y, ps[19].z)) << format_names[int(e)];
  }
}

TEST(Ply, RadiusGivesEverySphereOne) {
  const std::vector<particle> ps = random_particles(50, 11);
  for (bool has_radius : {false, true}) {
    api::particles o;
    o.radius = 0.125;
    const api::scene p = read_ok(ply_of(ps, enc::little, has_radius), o);
    ASSERT_TRUE(p.arrays);
    for (size_t k = 0; k < ps.size(); ++k) EXPECT_EQ(p.arrays->at(k).radius, 0.125);
  }
  const scene_file_error e = refused(ply_of(ps, enc::little, false));
  EXPECT_EQ(e.path, "radius");
  EXPECT_NE(e.message.find("the file gives no radius and no types: give --radius R"), std::string::npos) << e.message;
}

// --color-by: the property through the colormap over its min and max, or
// over --color-range (values beyond it take the ends).
TEST(Ply, ColorByMapsAPropertyThroughTheColormap) {
  const std::vector<particle> ps = random_particles(300, 13);  // ids 0 ... 299
  for (colormap m : {colormap::viridis, colormap::magma, colormap::gray}) {
    api::particles o;
    o.color_by = "id";
    o.colormap = colormap_names[size_t(m)];
    const api::scene p = read_ok(ply_of(ps, enc::ascii), o);
    ASSERT_TRUE(p.arrays);
    EXPECT_EQ(p.arrays->shade, shading::lit);
    for (size_t k : {size_t(0), size_t(150), size_t(299)}) {
      const std::array<float, 3> want = colormap_color(m, double(k), 0.0, 299.0);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(p.arrays->colors.get(k, c), double(want[size_t(c)]));
    }
    o.color_range = std::array<double, 2>{100.0, 200.0};
    const api::scene q = read_ok(ply_of(ps, enc::little), o);
    EXPECT_EQ(q.arrays->colors.get(0, 0), double(colormap_color(m, 100.0, 100.0, 200.0)[0]));
    EXPECT_EQ(q.arrays->colors.get(299, 1), double(colormap_color(m, 200.0, 100.0, 200.0)[1]));
  }
  // matplotlib's lookup: entry floor(256 t), the last at t = 1; gray's entry k is k / 255.
  EXPECT_EQ(colormap_color(colormap::gray, 0.5, 0.0, 1.0)[0], 128.0f / 255.0f);
  EXPECT_EQ(colormap_color(colormap::gray, 1.0, 0.0, 1.0)[2], 1.0f);
  EXPECT_EQ(colormap_color(colormap::gray, -7.0, 0.0, 1.0)[1], 0.0f);
  EXPECT_EQ(colormap_color(colormap::viridis, 0.0, 0.0, 1.0)[0], 0.267004f);
  EXPECT_EQ(colormap_color(colormap::magma, 1.0, 0.0, 1.0)[2], 0.749504f);
  // A range as wide as the doubles: no difference overflows.
  EXPECT_EQ(colormap_color(colormap::viridis, 1.7e308, -1.7e308, 1.7e308)[0], 0.993248f);
  EXPECT_EQ(colormap_color(colormap::viridis, -1.7e308, -1.7e308, 1.7e308)[0], 0.267004f);
  EXPECT_EQ(colormap_color(colormap::viridis, 0.0, -1.7e308, 1.7e308)[1], colormap_color(colormap::viridis, 0.5, 0.0, 1.0)[1]);
  api::particles o;
  o.color_by = "ids";
  const scene_file_error e = refused(ply_of(ps, enc::little), o);
  EXPECT_EQ(e.path, "color_by");
  EXPECT_NE(e.message.find("'ids' is not a column of this frame"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("did you mean id?"), std::string::npos) << e.message;
}

struct hostile {
  const char* what;
  std::string bytes;
  std::string path, message;  // message: a part of it
};

std::string head(const std::string& format, const std::string& vertex_count, const std::string& props) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + vertex_count + "\n" + props + "end_header\n";
}
const std::string xyzr = "property float x\nproperty float y\nproperty float z\nproperty float radius\n";

std::string floats(std::initializer_list<float> v) {
  std::string s;
  for (float f : v) put(s, f, false);
  return s;
}

std::vector<hostile> hostile_files() {
  const std::string le = "binary_little_endian";
  const std::string h2 = head(le, "2", xyzr);  // 2 rows of 16 bytes from byte h2.size()
  const std::string two = floats({0, 0, -1, 0.5f, 1, 0, -1, 0.5f});
  const auto at = [](size_t b) { return "(at byte " + std::to_string(b) + ")"; };
  const std::string unended = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n";
  const std::string faces = "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uchar int i\n"
                            "element vertex 1\n" + xyzr + "end_header\n";
  return {
      {"not PLY", "{\"spheres\": []}\n", "", "is not a PLY file: it does not begin with a line 'ply' (at byte 0)"},
      {"no end_header", unended, "header", "ends without end_header " + at(unended.size())},
      {"a header that never ends", "ply\nformat ascii 1.0\n" + std::string(1 << 21, '\n'), "header",
       "has no end_header in its first 1048576 bytes"},
      {"unknown type", head(le, "1", "property float x\nproperty flaot y\n"), "vertex.y",
       "'flaot' is not one of char, uchar"},
      {"a list in vertex", head(le, "1", xyzr + "property list uchar int neighbours\n"), "vertex.neighbours",
       "a list property"},
      {"a count that promises more", head(le, "1000", xyzr) + two, "vertex",
       "the header promises 1000 vertices of 16 bytes from byte " + std::to_string(head(le, "1000", xyzr).size()) +
           ", but the file ends after 2 of them"},
      {"a truncated body", h2 + two.substr(0, 30), "vertex", "the file ends after 1 of them " + at(h2.size() + 30)},
      {"a huge ASCII count", head("ascii", "4000000000", xyzr) + "0 0 -1 1\n", "vertex",
       "the header promises 4000000000 vertices of 4 numbers; the 9 bytes left hold at most 1"},
      {"more vertices than spheres", head(le, "5000000000", xyzr), "vertex",
       "5000000000 vertices; at most 4294967295 spheres"},
      {"an ASCII file cut short", head("ascii", "3", xyzr) + "0 0 -1 1\n0 0 -2 1\n0 0 -3\n", "vertex",
       "the file ends after 2 of 3 vertices"},
      {"not a number", head("ascii", "1", xyzr) + "0 zero -1 1\n", "vertex[0].y",
       "'zero' is not a number " + at(head("ascii", "1", xyzr).size() + 2)},
      {"a uchar out of range", head("ascii", "1", xyzr + "property uchar red\nproperty uchar green\nproperty uchar blue\n") +
                                   "0 0 -1 1 300 0 0\n",
       "vertex[0].red", "'300' is not a uchar (a whole number from 0 to 255)"},
      {"a NaN radius", h2 + floats({0, 0, -1, 0.5f, 1, 0, -1, NAN}), "vertex[1].radius",
       "nan is not a finite radius " + at(h2.size() + 16 + 12)},
      {"an infinite radius", h2 + floats({0, 0, -1, INFINITY, 1, 0, -1, 1}), "vertex[0].radius",
       "inf is not a finite radius " + at(h2.size() + 12)},
      {"a negative radius", h2 + floats({0, 0, -1, -0.5f, 1, 0, -1, 1}), "vertex[0].radius",
       "-0.5 is too small for a radius (it must be above 0)"},
      {"a zero radius", h2 + floats({0, 0, -1, 0, 1, 0, -1, 1}), "vertex[0].radius", "0 is too small for a radius"},
      {"a NaN centre", h2 + floats({0, NAN, -1, 1, 1, 0, -1, 1}), "vertex[0].y", "nan is not a finite number"},
      {"zero vertices", head(le, "0", xyzr), "vertex", "has no vertices: nothing to render"},
      {"no vertex element", "ply\nformat ascii 1.0\nelement face 0\nend_header\n", "header",
       "has no vertex element"},
      {"integer coordinates", head(le, "1", "property int x\nproperty int y\nproperty int z\nproperty float radius\n"),
       "vertex.x", "is int; want float or double"},
      {"mixed coordinate types",
       head(le, "1", "property float x\nproperty double y\nproperty float z\nproperty float radius\n"), "vertex.x",
       "the three must have one type"},
      {"a bad format", "ply\nformat binary_middle_endian 1.0\nend_header\n", "header",
       "format: 'binary_middle_endian' is not one of ascii, binary_little_endian, binary_big_endian"},
      {"a property declared twice", head(le, "1", xyzr + "property float x\n"), "vertex.x", "is declared twice"},
      {"faces cut short before the vertices", faces + "\x05" + floats({1, 2}), "face",
       "the file ends inside row 0 " + at(faces.size() + 9)},
      {"a uchar list count of 200 in an ASCII face", "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int i\n"
                                                     "element vertex 1\n" + xyzr + "end_header\n200 1 2\n",
       "face", "the file ends inside row 0"},
  };
}

// A count the file cannot hold is refused before --color-by's values are
// allocated for it (4294967295 doubles: 34 GB).
TEST(Ply, ACountIsCheckedBeforeAnythingIsAllocatedForIt) {
  api::particles o;
  o.color_by = "x";
  for (const char* format : {"binary_little_endian", "ascii"}) {
    const scene_file_error e = refused(head(format, "4294967295", xyzr) + "0 0 -1 1\n", o);
    EXPECT_EQ(e.path, "vertex") << e.message;
    EXPECT_NE(e.message.find("the header promises 4294967295 vertices"), std::string::npos) << e.message;
  }
}

TEST(Ply, HostileFilesAreRefusedWithThePartAndTheByte) {
  for (const hostile& h : hostile_files()) {
    const scene_file_error e = refused(h.bytes);
    EXPECT_EQ(e.path, h.path) << h.what << ": " << e.message;
    EXPECT_NE(e.message.find(h.message), std::string::npos) << h.what << ": " << e.message;
    EXPECT_NE(e.message.find("(at byte "), std::string::npos) << h.what << ": " << e.message;
    EXPECT_EQ(e.message.find('\n'), std::string::npos) << h.what;
    EXPECT_FALSE(e.io) << h.what;
  }
}

// A file that changes while it is read (its length or times differ after
// the read, or the read comes back short) is refused, not half read.
TEST(Ply, AFileThatChangesWhileReadIsRefused) {
  const std::string bytes = ply_of(random_particles(100, 17), enc::little);
  auto r = read_ply(memory(bytes, false), {});
  ASSERT_TRUE(std::holds_alternative<scene_file_error>(r));
  EXPECT_NE(std::get<scene_file_error>(r).message.find("changed while being read"), std::string::npos);
  byte_source shrinking = memory(bytes);
  shrinking.read = [&bytes](uint64_t offset, size_t n, char* to) {  // the body comes back a row short
    const size_t got = std::min(n, bytes.size() - 23 - size_t(offset));
    std::memcpy(to, bytes.data() + offset, got);
    return ptrdiff_t(got);
  };
  r = read_ply(shrinking, {});
  ASSERT_TRUE(std::holds_alternative<scene_file_error>(r));
  EXPECT_NE(std::get<scene_file_error>(r).message.find("changed while being read"), std::string::npos);
}

// What a file is comes from its content where a format has a signature,
// else from its name (which is all a missing file has).
TEST(Ply, TheRegistryTellsAFileByItsContentThenItsName) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("raycast-registry-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::vector<particle> ps = random_particles(10, 3);
  const auto write = [&](const char* name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  };
  EXPECT_EQ(formats::detect(write("a.json", ply_of(ps, enc::little))).particles, &ply_format());
  EXPECT_EQ(formats::detect(write("b.ply", json_of(ps))).scene, formats::scene_formats()[0]);
  EXPECT_EQ(formats::detect(write("noext", ply_of(ps, enc::ascii))).particles, &ply_format());
  EXPECT_EQ(formats::detect((dir / "missing.PLY").string()).particles, &ply_format());
  EXPECT_FALSE(formats::detect((dir / "missing.txt").string()));
  EXPECT_TRUE(formats::names_a_file((dir / "missing.ply").string()));
  EXPECT_TRUE(formats::names_a_file((dir / "noext").string()));
  EXPECT_FALSE(formats::names_a_file(".ply"));
  EXPECT_FALSE(formats::names_a_file("world"));
  std::filesystem::remove_all(dir);
}

// The library's load_scene reads a particle file with the command line's
// options, keeps its memory alive in the scene, and refuses the options for
// a scene file that is not PLY, naming the keyword.
TEST(Ply, TheLibraryLoadsAParticleFile) {
  namespace rc = raycast::api;
  const std::vector<particle> ps = random_particles(400, 31);
  const std::string dir = ::testing::TempDir();
  const std::string ply = dir + "/api_particles.ply", json = dir + "/api_particles.json";
  {
    std::FILE* f = std::fopen(ply.c_str(), "wb");
    const std::string bytes = ply_of(ps, enc::big, false, false);
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
    std::fclose(f);
    f = std::fopen(json.c_str(), "wb");
    std::fputs(json_of(ps).c_str(), f);
    std::fclose(f);
  }
  rc::particles shape;
  shape.radius = 0.2;
  shape.color_by = "id";
  shape.colormap = "gray";
  rc::scene s = rc::load_scene(ply, shape);
  ASSERT_TRUE(s.arrays);
  EXPECT_TRUE(s.arrays->owner);
  EXPECT_EQ(s.arrays->count, ps.size());
  EXPECT_EQ(s.arrays->shade, rc::shading::lit);
  s.cam.width = 64;
  s.cam.lookfrom = {0.5, 1.0, 3.0};
  s.cam.lookat = rc::vec3{0.0, 0.0, -5.0};
  const rc::scene copy = s;  // shares the file's memory
  s = rc::scene{};
  const rc::image img = rc::render(copy, {});
  EXPECT_EQ(img.width, 64);
  rc::particles radius;  // every sphere's, in a scene file too
  radius.radius = 1.0;
  for (const rc::sphere& b : rc::load_scene(json, radius).spheres) EXPECT_EQ(b.radius, 1.0);
  try {
    rc::particles by;
    by.color_by = "id";
    rc::load_scene(json, by);
    ADD_FAILURE() << "no error";
  } catch (const rc::error& e) {
    EXPECT_EQ(e.field(), "color_by");
    EXPECT_NE(e.message().find("applies to particle files only"), std::string::npos) << e.what();
  }
  try {
    shape.colormap = "jet";
    rc::load_scene(ply, shape);
    ADD_FAILURE() << "no error";
  } catch (const rc::error& e) {
    EXPECT_EQ(e.field(), "colormap");
  }
  std::remove(ply.c_str());
  std::remove(json.c_str());
}

}  // namespace
