// The GSD reader on files made here (tests/formats/gsd_writer.h): what it
// reads, and the hostile files it refuses with one line naming the block or
// frame and the byte: cut short, a count that lies, NaN coordinates,
// missing positions, absurd counts, types out of range, what is not GSD.
// The files of the gsd package's own writer are test_formats_tools.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "formats/gsd/hoomd.h"
#include "formats/gsd_writer.h"
#include "formats/text_support.h"

namespace {

using namespace raycast;
using namespace raycast::formats;
using raycast_test::gsd_out;
using raycast_test::refusal;

const std::vector<float> box = {4, 5, 6, 0, 0, 0};
const std::vector<float> xyz = {0, 0, 0, 1, 1, 1, -1, -1, -1};

std::vector<gsd_out> frame0() { return raycast_test::hoomd_frame(0, xyz, {0, 1, 1}, {"A", "B"}, {1, 2, 3}, box); }

// The positions chunk's byte: after the header, the box (24 bytes) and N (4).
constexpr uint64_t position_at = 256 + 24 + 4;

std::unique_ptr<trajectory> open(const std::string& bytes) {
  auto keep = std::make_shared<std::string>(bytes);
  return open_gsd(reinterpret_cast<const unsigned char*>(keep->data()), keep->size(), keep);
}

std::string read_refusal(const std::string& bytes, size_t k = 0) {
  return refusal([&] { open(bytes)->read(k, {}); });
}

uint64_t le(const std::string& s, size_t at, int n) {
  uint64_t v = 0;
  for (int b = n - 1; b >= 0; --b) v = (v << 8) | uint8_t(s[at + size_t(b)]);
  return v;
}
uint64_t index_at(const std::string& f) { return le(f, 8, 8); }
// The index entry of chunk c (in the order written).
uint64_t entry(const std::string& f, size_t c) { return index_at(f) + 32 * c; }

TEST(GsdLayer, ReadsAFrameInPlace) {
  for (uint32_t version : {2u << 16, 1u << 16}) {
    const std::string bytes = raycast_test::write_gsd(frame0(), "hoomd", version);
    EXPECT_TRUE(gsd_format().sniff(bytes));
    auto t = open(bytes);
    ASSERT_EQ(t->frame_count(), 1u);
    const particle_frame f = t->read(0, {});
    ASSERT_EQ(f.count, 3u);
    EXPECT_EQ(f.positions.get(2, 1), -1.0);
    EXPECT_EQ(f.positions.type, api::element::f32);
    EXPECT_EQ(f.type_names, (std::vector<std::string>{"A", "B"}));
    EXPECT_EQ(f.types->get(2), 1.0);
    EXPECT_EQ(f.radii->get(2), 1.5);
    EXPECT_EQ(f.cell->origin, (api::vec3{-2, -2.5, -3}));
    EXPECT_EQ(f.timestep, 0);  // the schema's default
  }
  EXPECT_FALSE(gsd_format().sniff("ITEM: TIMESTEP\n"));
}

TEST(GsdLayer, HostileFilesAreRefusedNamingTheByte) {
  const std::string ok = raycast_test::write_gsd(frame0());
  EXPECT_EQ(read_refusal(ok.substr(0, 100)), "header (byte 100): the file is shorter than GSD's 256-byte header");
  EXPECT_EQ(read_refusal("ITEM: TIMESTEP" + std::string(300, '\n')), "header (byte 0): not a GSD file (no magic number)");
  EXPECT_EQ(read_refusal(ok.substr(0, ok.size() - 40)),
            "header (byte 8): the index (10 entries at byte " + std::to_string(index_at(ok)) + ") lies past the file's end");
  std::string absurd = ok;
  raycast_test::put_le(absurd, 16, uint64_t(1) << 60, 8);
  EXPECT_EQ(read_refusal(absurd), "header (byte 8): the index (1152921504606846976 entries at byte " +
                                      std::to_string(index_at(ok)) + ") lies past the file's end");
  std::string names = ok;
  raycast_test::put_le(names, 32, uint64_t(1) << 59, 8);
  EXPECT_TRUE(read_refusal(names).starts_with("header (byte 24): the name list (576460752303423488 segments at byte "));
  std::string huge = ok;
  raycast_test::put_le(huge, entry(ok, 2) + 8, 1000000000000000, 8);
  EXPECT_EQ(read_refusal(huge), "index (byte " + std::to_string(entry(ok, 2)) +
                                    "): particles/position (1000000000000000 x 3 at byte 284) lies past the file's end");
  std::string type = ok;
  type[entry(ok, 2) + 30] = 42;
  EXPECT_EQ(read_refusal(type), "index (byte " + std::to_string(entry(ok, 2)) + "): type 42 is not a GSD type");
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(frame0(), "other")), "header (byte 112): the schema is 'other', not hoomd");
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(frame0(), "hoomd", 3u << 16)),
            "header (byte 44): GSD file layer version 3.0 is not one this reader knows (1.0 to 2.x)");
  EXPECT_EQ(read_refusal(ok, 5), "frame 5: the file has 1 frames");
}

TEST(GsdLayer, HostileFramesAreRefusedNamingFrameAndByte) {
  auto lying = frame0();
  lying[1].bytes = raycast_test::gsd_bytes(std::vector<uint32_t>{5});
  std::string f = raycast_test::write_gsd(lying);
  EXPECT_EQ(read_refusal(f), "frame 0 (byte " + std::to_string(entry(f, 2)) + "): particles/position has 3 rows; particles/N is 5");
  auto nan = frame0();
  std::vector<float> p = xyz;
  p[4] = std::numeric_limits<float>::quiet_NaN();
  nan[2].bytes = raycast_test::gsd_bytes(p);
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(nan)),
            "frame 0 (byte " + std::to_string(position_at + 16) + "): particles/position of particle 1 is not finite");
  p[4] = -std::numeric_limits<float>::infinity();
  nan[2].bytes = raycast_test::gsd_bytes(p);
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(nan)),
            "frame 0 (byte " + std::to_string(position_at + 16) + "): particles/position of particle 1 is not finite");
  auto missing = frame0();
  missing.erase(missing.begin() + 2);
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(missing)),
            "frame 0 (byte 280): particles/N is 3 but there is no particles/position (in this frame or frame 0)");
  const std::string typed = raycast_test::write_gsd(raycast_test::hoomd_frame(0, xyz, {0, 1, 7}, {"A", "B"}, {}, box));
  const uint64_t typeid_at = position_at + 36 + 4;  // after the positions and the two names of 2 bytes
  EXPECT_EQ(read_refusal(typed), "frame 0 (byte " + std::to_string(typeid_at + 8) +
                                     "): particles/typeid of particle 2 is 7; there are 2 types");
  auto bad_box = frame0();
  bad_box[0].bytes = raycast_test::gsd_bytes(std::vector<float>{4, -5, 6, 0, 0, 0});
  EXPECT_EQ(read_refusal(raycast_test::write_gsd(bad_box)), "frame 0 (byte 260): configuration/box is not a box");
}

TEST(GsdLayer, LaterFramesInheritFrameZerosChunks) {
  auto chunks = frame0();
  chunks.push_back({1, "particles/position", 9, 3, 3, raycast_test::gsd_bytes(std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8, 9})});
  chunks.push_back({2, "particles/N", 3, 1, 1, raycast_test::gsd_bytes(std::vector<uint32_t>{2})});
  chunks.push_back({2, "particles/position", 9, 2, 3, raycast_test::gsd_bytes(std::vector<float>{1, 1, 1, 2, 2, 2})});
  auto t = open(raycast_test::write_gsd(chunks));
  ASSERT_EQ(t->frame_count(), 3u);
  const particle_frame f1 = t->read(1, {}), f2 = t->read(2, {});
  EXPECT_EQ(f1.count, 3u);
  EXPECT_EQ(f1.radii->get(1), 1.0);
  EXPECT_EQ(f1.types->get(1), 1.0);
  EXPECT_EQ(f1.positions.get(2, 2), 9.0);
  EXPECT_EQ(f2.count, 2u);
  EXPECT_EQ(f2.radii->get(1), 0.5);  // the count changed: the default diameter
  EXPECT_EQ(f2.types->get(1), 0.0);
  EXPECT_EQ(f2.type_names, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(f2.cell->a, (api::vec3{4, 0, 0}));
}

}  // namespace
