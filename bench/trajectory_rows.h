// raycast-bench's trajectory rows: what a run of raycast over a LAMMPS
// trajectory costs against its frames, end to end (the program as a user
// runs it: read ahead, prepare, render, write each frame's PNG).
//   frames/A/F/WxH   `raycast --scene DUMP -o DIR/f_%04d.png --threads 1
//       --stats -q` on an F-frame dump of A atoms a frame (bench/formats_rows.h,
//       framed by default, lit), beside a one-frame run of the same file
//       (`--frames 0`), both in each iteration; the raycast beside this
//       program (the build tree's, or the installed one)
// Rows (A, F, size): (10^5, 12, 1920x1080), a frame as a user renders it,
// and (2000, 1000, 640x360), a long trajectory, to show no growth; --quick:
// (10^4, 12, 480x270) and (2000, 100, 480x270).
// Counters (medians of 3 repetitions): seconds, load, prepare, render, open,
// write and peak_rss_mb of the F-frame run (raycast's own --stats; load is
// summed over the frames, read on a thread of their own while the one before
// renders) and the same with one_ of the one-frame run. report.py compares
// them: seconds against F x (prepare + render) + load of one frame, and
// against the one-frame run plus F - 1 more frames' prepare + render + write;
// peak_rss_mb against the one-frame run's.
#pragma once

namespace raycast::bench {

void register_trajectory_rows(bool quick);

}  // namespace raycast::bench
