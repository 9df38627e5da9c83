// The text readers (LAMMPS dumps, XYZ) on texts made here: what they take,
// and every hostile class refused with its one line naming the frame and
// the line: cut short, NaN or infinite coordinates, missing positions, a
// count that lies, a value that is not a number, absurd counts, gzip bombs
// (memory bounded), corrupt gzip. Also: frames read in order read each byte
// once, and detection by content and by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <random>
#include <utility>
#include <string>

#include "formats/input/fields.h"
#include "formats/input/line_cursor.h"
#include "formats/lammps/lammps_dump.h"
#include "formats/xyz/extxyz.h"
#include "formats/text_support.h"

namespace {

using namespace raycast;
using namespace raycast::formats;
using raycast_test::refusal;

// The header of a dump frame: timestep, count, an orthogonal box, columns.
std::string head(int step, uint64_t n, const std::string& columns = "id type x y z") {
  return "ITEM: TIMESTEP\n" + std::to_string(step) + "\nITEM: NUMBER OF ATOMS\n" + std::to_string(n) +
         "\nITEM: BOX BOUNDS pp pp ff\n0 10\n0 20\n-5 5\nITEM: ATOMS " + columns + "\n";
}

std::unique_ptr<trajectory> dump(const std::string& text) {
  return open_lammps_dump(input::memory_text(text.data(), text.size()));
}
std::unique_ptr<trajectory> xyz(const std::string& text) { return open_xyz(input::memory_text(text.data(), text.size())); }

// read(k) on a fresh trajectory, and the same after frame_count() (the scan):
// both must refuse with the same line.
template <class Open>
std::string read_refusal(Open open, const std::string& text, size_t k = 0) {
  const std::string direct = refusal([&] { open(text)->read(k, {}); });
  const std::string scanned = refusal([&] {
    auto t = open(text);
    t->frame_count();
    t->read(k, {});
  });
  EXPECT_EQ(direct, scanned);
  return direct;
}

// The value strtod gives a whole field, or nullopt where it takes less (or
// reads hexadecimal, which no simulation code writes and we do not take).
std::optional<double> strtod_of(const std::string& f) {
  if (f.find_first_of("xX") != std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(f.c_str(), &end);
  if (f.empty() || end != f.c_str() + f.size()) return std::nullopt;
  return v;
}

TEST(NumberFields, TheFastPathsGiveStrtodsValuesToTheLastBit) {
  std::mt19937_64 rng(99);
  std::vector<std::string> cases = {"0", "-0", "0.", "-0.", ".5", "-.5", "1234567.1234567", "12345678", "1.23456789",
                                    "9999999.9999999", "0.1", "-4.49651", "1e5", "1.5e-300", "nan", "-inf", "+1.5",
                                    "-", ".", "1.2.3", "--1", "1-", "0x10", "7.", "00000001.5"};
  for (int k = 0; k < 200000; ++k) {  // what %g, %.8f and %.17g write
    const double x = std::ldexp(double(rng() >> 11), -int(rng() % 80)) * (rng() % 2 ? 1 : -1);
    char b[64];
    std::snprintf(b, sizeof b, k % 3 == 0 ? "%g" : k % 3 == 1 ? "%.8f" : "%.17g", x);
    cases.push_back(b);
  }
  for (const std::string& c : cases) {
    const std::string padded = c + std::string(input::line_padding, '9');  // digits past the end: never read
    const char* e = padded.data() + c.size();
    double fast = 0, slow = 0;
    const char* f = input::parse_decimal_padded(padded.data(), e, fast);
    const char* g = input::parse_number(padded.data(), e, slow);
    const auto want = strtod_of(c);
    if (f) {
      ASSERT_EQ(f, e) << c;
      ASSERT_TRUE(want) << c;
      ASSERT_EQ(std::bit_cast<uint64_t>(fast), std::bit_cast<uint64_t>(*want)) << c;
    }
    if (!want) {
      ASSERT_TRUE(g == nullptr || g != e) << c;
      continue;
    }
    ASSERT_EQ(g, e) << c;
    if (std::isnan(*want)) ASSERT_TRUE(std::isnan(slow)) << c;
    else ASSERT_EQ(std::bit_cast<uint64_t>(slow), std::bit_cast<uint64_t>(*want)) << c;
  }
}

TEST(LammpsDumpText, ColumnsInAnyOrderRowsInAnyOrder) {
  const std::string text = head(7, 3, "z vx type y id x radius") + "3 0.5 2 2 30 1\t0.25\n-1 0 1 1 10 0 0.5\n0 0 2 0 20 9.5 1\n";
  const particle_frame f = dump(text)->read(0, {});
  ASSERT_EQ(f.count, 3u);
  EXPECT_EQ((api::vec3{f.positions.get(0, 0), f.positions.get(0, 1), f.positions.get(0, 2)}), (api::vec3{1, 2, 3}));
  EXPECT_EQ(f.positions.get(2, 0), 9.5);
  EXPECT_EQ(f.types->get(1), 0.0);
  EXPECT_EQ(f.type_names, (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(f.radii->get(0), 0.25);
  EXPECT_TRUE(f.properties.empty());  // none wanted
  EXPECT_EQ(f.timestep, 7);
  EXPECT_EQ(f.cell->c, (api::vec3{0, 0, 10}));
  EXPECT_EQ(f.cell->origin, (api::vec3{0, 0, -5}));
  EXPECT_EQ(f.cell->periodic, (std::array<bool, 3>{true, true, false}));
  wanted_columns w;
  w.properties = {"vx", "id"};
  const particle_frame g = dump(text)->read(0, w);
  ASSERT_EQ(g.properties.size(), 2u);
  EXPECT_EQ(g.properties[0].name, "vx");
  EXPECT_EQ(g.property("id")->values.get(2), 20.0);
  // A diameter is halved into the radius; element symbols are the type names.
  const particle_frame d = dump(head(0, 2, "x y z diameter element") + "0 0 0 3 Fe\n1 1 1 1 O\n")->read(0, {});
  EXPECT_EQ(d.radii->get(0), 1.5);
  EXPECT_EQ(d.type_names, (std::vector<std::string>{"Fe", "O"}));
  EXPECT_EQ(d.types->get(1), 1.0);
}

TEST(LammpsDumpText, TriclinicScaledPositionsAreCornerPlusFractionsOfTheEdges) {
  // Bounds of the box with lo (1, 2, 3), lx 10, ly 8, lz 6 and tilts xy 2, xz -1, yz 3.
  const std::string text =
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS xy xz yz pp pp pp\n0 13 2\n2 13 -1\n3 9 3\n"
      "ITEM: ATOMS id xs ys zs\n1 0 0 0\n2 1 0.5 0.25\n";
  const particle_frame f = dump(text)->read(0, {});
  EXPECT_EQ(f.cell->origin, (api::vec3{1, 2, 3}));
  EXPECT_EQ(f.cell->a, (api::vec3{10, 0, 0}));
  EXPECT_EQ(f.cell->b, (api::vec3{2, 8, 0}));
  EXPECT_EQ(f.cell->c, (api::vec3{-1, 3, 6}));
  EXPECT_EQ(f.positions.get(0, 0), 1.0);
  EXPECT_EQ((api::vec3{f.positions.get(1, 0), f.positions.get(1, 1), f.positions.get(1, 2)}),
            (api::vec3{1 + 10 + 1 - 0.25, 2 + 4 + 0.75, 3 + 1.5}));
}

TEST(LammpsDumpText, SkipsSectionsOfNoConcernAndBlankLinesBetweenFrames) {
  const std::string text = "ITEM: UNITS\nlj\nITEM: TIME\n0.5\n" + head(1, 1) + "1 1 0 0 0\n\n\n" + head(2, 1) + "1 1 1 1 1\n\n";
  auto t = dump(text);
  EXPECT_EQ(t->frame_count(), 2u);
  EXPECT_EQ(t->read(1, {}).timestep, 2);
}

TEST(LammpsDumpText, HostileDumpsAreRefusedNamingFrameAndLine) {
  const std::string ok = head(0, 2) + "1 1 0 0 0\n2 1 1 1 1\n";
  EXPECT_EQ(read_refusal(dump, head(0, 3) + "1 1 0 0 0\n2 1 1 1 1\n"),
            "frame 0 (line 12): the header promises 3 atoms; the file ends after 2");
  EXPECT_EQ(read_refusal(dump, ok + head(10, 2) + "1 1 0 0 0\n", 1),
            "frame 1 (line 22): the header promises 2 atoms; the file ends after 1");
  EXPECT_EQ(read_refusal(dump, head(0, 1) + "1 1 nan 0 0\n"), "frame 0 (line 10): x is not finite: 'nan'");
  EXPECT_EQ(read_refusal(dump, head(0, 2) + "1 1 0 0 0\n2 1 1 -inf 1\n"), "frame 0 (line 11): y is not finite: '-inf'");
  EXPECT_EQ(read_refusal(dump, head(0, 1, "id type x y") + "1 1 0 0\n"),
            "frame 0 (line 9): no position columns (x y z, xu yu zu, xs ys zs or xsu ysu zsu)");
  EXPECT_EQ(read_refusal(dump, ok + head(10, 2) + "1 1 0 0 0\n2 1 1 1.5abc 1\n", 1),
            "frame 1 (line 22): y is not a number: '1.5abc'");
  EXPECT_EQ(read_refusal(dump, head(0, 1) + "1 1 0 0\n"), "frame 0 (line 10): the row has 4 values; ITEM: ATOMS names 5");
  EXPECT_EQ(read_refusal(dump, head(0, 1) + "1 1 0 0 0 7\n"),
            "frame 0 (line 10): the row has more values than the 5 ITEM: ATOMS names");
  EXPECT_EQ(read_refusal(dump, head(0, 1) + "1 0 0 0 0\n"), "frame 0 (line 10): type 0 is not a LAMMPS type (1 to 65536)");
  EXPECT_EQ(read_refusal(dump, "hello\n"), "frame 0 (line 1): expected an ITEM: line, found 'hello'");
  EXPECT_EQ(read_refusal(dump, "ITEM: TIMESTEP\nten\n"), "frame 0 (line 2): ITEM: TIMESTEP is not a whole number: 'ten'");
  EXPECT_EQ(read_refusal(dump, "ITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n7 5\nITEM: ATOMS x y z\n0 0 0\n"),
            "frame 0 (line 6): the box's upper bound lies below its lower bound");
  EXPECT_EQ(read_refusal(dump, ok, 1), "frame 1: the file has 1 frames");
}

TEST(LammpsDumpText, AbsurdCountsAreRefusedWithoutAllocatingForThem) {
  const double before = raycast_test::peak_rss();
  // Ten bytes a row at least: the table has room for the two rows there are
  // (and one), not 10^12.
  EXPECT_EQ(read_refusal(dump, head(0, 1000000000000) + "1 1 0 0 0\n2 1 0 0 0\n"),
            "frame 0 (line 12): the header promises 1000000000000 atoms; the file ends after 2");
  // gzip: deflate expands 1032 times at most; the text has one row.
  const std::string gz = raycast_test::gzip(head(0, 1000000000000000) + "1 1 0 0 0\n");
  EXPECT_EQ(read_refusal(dump, gz), "frame 0 (line 11): the header promises 1000000000000000 atoms; the file ends after 1");
  EXPECT_LT(raycast_test::peak_rss() - before, 16e6);
}

TEST(LammpsDumpText, GzippedDumpsReadAsPlainAndCorruptOnesAreRefused) {
  const std::string text = head(0, 2, "id type x y z vx") + "1 1 0 0 0 0.5\n2 2 1 1 1 -0.5\n" + head(10, 1) + "1 1 2 2 2\n";
  const std::string gz = raycast_test::gzip(text);
  auto t = dump(gz);
  ASSERT_EQ(t->frame_count(), 2u);
  EXPECT_EQ(t->read(1, {}).positions.get(0, 2), 2.0);
  EXPECT_EQ(t->read(0, {}).positions.get(1, 1), 1.0);
  // Two members, as `cat a.gz b.gz` makes, are one text.
  EXPECT_EQ(dump(raycast_test::gzip(text.substr(0, 40)) + raycast_test::gzip(text.substr(40)))->frame_count(), 2u);
  const std::string cut = read_refusal(dump, gz.substr(0, gz.size() - 12), 1);
  EXPECT_TRUE(cut.starts_with("frame ") && cut.find("the gzip stream is cut short at byte ") != std::string::npos) << cut;
  std::string bad = gz;
  for (size_t k = 20; k < 40; ++k) bad[k] = char(0xff);
  const std::string corrupt = read_refusal(dump, bad);
  EXPECT_TRUE(corrupt.starts_with("frame 0 (line 1): the gzip stream is corrupt")) << corrupt;
}

TEST(LammpsDumpText, GzipBombsKeepMemoryBounded) {
  // 128 MiB of one endless row, deflated into a few hundred KiB.
  size_t chunks = 0;
  const std::string line_bomb = raycast_test::gzip_stream([&](std::string& in) {
    in = chunks == 0 ? head(0, 1) : "";
    in.append(size_t(1) << 20, '7');
    return ++chunks < 128;
  });
  EXPECT_LT(line_bomb.size(), size_t(1) << 20);  // deflate's 1032:1
  // A frame, then 128 MiB of blank lines.
  chunks = 0;
  const std::string blank_bomb = raycast_test::gzip_stream([&](std::string& in) {
    in = chunks == 0 ? head(0, 1) + "1 1 0 0 0\n" : "";
    in.append(size_t(1) << 20, '\n');
    return ++chunks < 128;
  });
  // Reading them: the endless row is refused at the window's bound, the blank
  // lines stream through the window; neither holds what it inflates (a
  // window of 4 MiB grown by doubling, and the sanitizers' quarantine of what
  // was freed, are well under half a bomb).
  const double before = raycast_test::peak_rss();
  EXPECT_EQ(read_refusal(dump, line_bomb), "frame 0 (line 10): a line longer than 4194304 bytes");
  EXPECT_EQ(dump(blank_bomb)->frame_count(), 1u);
  const double grown = raycast_test::peak_rss() - before;
  EXPECT_LT(grown, 64e6) << "reading the bombs took " << grown / 1e6 << " MB";
}

TEST(LammpsDumpText, FramesReadInOrderReadEachByteOnce) {
  std::string text;
  for (int k = 0; k < 20; ++k) {
    text += head(k, 3);
    for (int r = 0; r < 3; ++r) text += std::to_string(r + 1) + " 1 " + std::to_string(k) + " 0 0\n";
  }
  const std::string gz = raycast_test::gzip(text);
  for (const std::string* bytes : {&std::as_const(text), &gz}) {
    raycast_test::source_counts n;
    auto t = open_lammps_dump(std::make_unique<raycast_test::counting_source>(input::memory_text(bytes->data(), bytes->size()), n));
    for (size_t k = 0; k < 20; ++k) ASSERT_EQ(t->read(k, {}).positions.get(2, 0), double(k));
    EXPECT_EQ(t->frame_count(), 20u);
    EXPECT_EQ(n.bytes, text.size());
    EXPECT_EQ(n.rewinds, 0u);
  }
}

TEST(LammpsDumpText, DetectedByContentAndName) {
  const format& f = lammps_dump_format();
  EXPECT_EQ(f.name, "lammps-dump");
  EXPECT_TRUE(f.sniff("ITEM: TIMESTEP\n0\n"));
  EXPECT_TRUE(f.sniff("\nITEM: UNITS\nlj\n"));
  EXPECT_FALSE(f.sniff("3\ncomment\n"));
  for (std::string_view e : {".lammpstrj", ".dump", ".lammpstrj.gz", ".dump.gz"})
    EXPECT_NE(std::find(f.extensions.begin(), f.extensions.end(), e), f.extensions.end()) << e;
  EXPECT_EQ(xyz_format().sniff, nullptr);
  EXPECT_NE(std::find(xyz_format().extensions.begin(), xyz_format().extensions.end(), ".extxyz"),
            xyz_format().extensions.end());
  EXPECT_EQ(refusal([&] { f.open("/nonexistent/dump.lammpstrj"); }), "No such file or directory");
  EXPECT_EQ(refusal([&] { f.open("/"); }), "is a directory, not a scene file");
}

TEST(XyzText, ExtendedAndPlainFrames) {
  const std::string text =
      "2\nLattice=\"4 0 0 0 5 0 1 0 6\" Properties=species:S:1:pos:R:3:forces:R:3:fixed:L:1:radius:R:1 "
      "info=\"a b\" pbc=\"T F T\" step=12\nCu 0 1 2 0.1 0.2 0.3 T 0.5\nAg 3 4 5 -1 -2 -3 F 0.25\n"
      "1\nplain comment, not key=value pairs \"\nC 7 8 9 extra fields\n";
  auto t = xyz(text);
  ASSERT_EQ(t->frame_count(), 2u);
  wanted_columns w;
  w.all = true;
  const particle_frame f = t->read(0, w);
  EXPECT_EQ(f.type_names, (std::vector<std::string>{"Cu", "Ag"}));
  EXPECT_EQ(f.positions.get(1, 2), 5.0);
  EXPECT_EQ(f.radii->get(1), 0.25);
  ASSERT_NE(f.property("forces"), nullptr);
  EXPECT_EQ(f.property("forces")->components, 3);
  EXPECT_EQ(f.property("forces")->values.get(1, 2), -3.0);
  EXPECT_EQ(f.property("fixed")->values.get(0), 1.0);
  EXPECT_EQ(f.cell->c, (api::vec3{1, 0, 6}));
  EXPECT_EQ(f.cell->periodic, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(f.timestep, 12);
  const particle_frame g = t->read(1, w);
  EXPECT_EQ(g.count, 1u);
  EXPECT_EQ(g.type_names, (std::vector<std::string>{"C"}));
  EXPECT_EQ(g.positions.get(0, 1), 8.0);
  EXPECT_FALSE(g.cell);
}

TEST(XyzText, HostileFilesAreRefusedNamingFrameAndLine) {
  const std::string ok = "1\nProperties=species:S:1:pos:R:3\nH 0 0 0\n";
  EXPECT_EQ(read_refusal(xyz, "3\n\nH 0 0 0\n"), "frame 0 (line 4): the header promises 3 atoms; the file ends after 1");
  EXPECT_EQ(read_refusal(xyz, "3\n\nH 0 0 0\nHe 1.5 2.5 3.5\n"), "frame 0 (line 5): the header promises 3 atoms; the file ends after 2");
  EXPECT_EQ(read_refusal(xyz, "1\n\nH nan 0 0\n"), "frame 0 (line 3): pos is not finite: 'nan'");
  EXPECT_EQ(read_refusal(xyz, "1\n\nH 0 0 inf\n"), "frame 0 (line 3): pos is not finite: 'inf'");
  EXPECT_EQ(read_refusal(xyz, "1\nProperties=species:S:1:where:R:3\nH 0 0 0\n"),
            "frame 0 (line 2): Properties has no pos (the positions)");
  EXPECT_EQ(read_refusal(xyz, ok + "2\n\nH 0 0 0\nHe x1 0 0\n", 1), "frame 1 (line 7): pos is not a number: 'x1'");
  EXPECT_EQ(read_refusal(xyz, "many\n\n"), "frame 0 (line 1): the atom count is not a whole number: 'many'");
  EXPECT_EQ(read_refusal(xyz, "1\n\nH 0 0\n"), "frame 0 (line 3): the row has 3 values; 4 expected");
  EXPECT_EQ(read_refusal(xyz, "1\nProperties=species:S:1:pos:R:3\nH 0 0 0 0\n"),
            "frame 0 (line 3): the row has more values than the 4 Properties names");
  EXPECT_EQ(read_refusal(xyz, "1\nProperties=species:S:1:pos:Q:3\nH 0 0 0\n"),
            "frame 0 (line 2): Properties has a bad entry 'pos:Q:3'");
  EXPECT_EQ(read_refusal(xyz, "1\nLattice=\"1 0 0 0 1 0 0 0\"\nH 0 0 0\n"),
            "frame 0 (line 2): Lattice is not nine finite numbers");
  EXPECT_EQ(read_refusal(xyz, "99999999999\n\nH 0 0 0\n"),
            "frame 0 (line 4): the header promises 99999999999 atoms; the file ends after 1");
}

}  // namespace
