// raycast-bench's particle-format rows (src/formats: LAMMPS dumps, GSD):
// what reading a simulation's frame costs, beside its peers in the same run.
//   formats/lammps/N/ours     open, read(0) of every column and frame_count()
//       of a LAMMPS text dump of N atoms (9 columns id type x y z vx vy vz
//       c_pe, written as LAMMPS's dump custom writes them: about 70 bytes an
//       atom), from the page cache, one thread
//   formats/lammps/N/ours-render  the same, with the columns a render reads
//       (positions, types; the other five skipped unparsed)
//   formats/lammps/N/numpy    numpy.loadtxt of the same file, timed inside
//       python3 (one run)
//   formats/lammps/N/ase      ase.io.read(format="lammps-dump-text") of it,
//       timed inside python3 (one run)
//   formats/lammps-gz/N/ours  the same file gzipped (zlib, level 6), read by us
//   formats/lammps-gz/N/inflate  zlib inflating that file alone, into a
//       window it drops: the decompressor's own speed
//   formats/gsd/N/ours        open and read(0) of a GSD frame of N particles
//       (position, typeid, types, diameter, box), from the page cache
//   formats/trajectory/lammps/M/F, formats/trajectory/lammps-gz/M/F
//       frames 0 .. F-1 of an F-frame dump of M atoms a frame, read in order
//       (F = 1 and F = 12), with the process's resident memory while each
//       frame is alive
// N = 10^6 and M = 10^5 (--quick: 10^4 and 10^3). The files are written
// once, deterministically, to $TMPDIR/raycast-bench-formats/ and kept there.
// Counters: seconds and cpu_seconds (the process's, every thread of it; the
// python peers' own), MB/s (of the text, or of the frame's chunks for GSD),
// and for the trajectories rss_growth_mb (the most resident memory with a
// frame alive less that with the first) and peak_rss_mb (the most); the
// ratios are report.py's.
#pragma once
#include <cstdint>
#include <string>

namespace raycast::bench {

void register_formats_rows(bool quick);

// The F-frame dump of n atoms a frame described above (written once to
// $TMPDIR/raycast-bench-formats/ and read once to warm the page cache); ""
// where it cannot be written.
std::string dump_file(int frames, int64_t n);

}  // namespace raycast::bench
