// raycast-bench's particle-file rows: what reading a PLY file costs against
// the machine's bare memory bandwidth, per sphere, beside the JSON rows.
//   load-ply/N   read_ply_file of the packed box of N spheres (x y z radius
//       floats and red green blue bytes: 19 bytes a sphere), from the page
//       cache: ns a sphere and GB/s; beside it, in the same iteration and
//       untimed, pread of the same file into memory (the page cache's floor)
//       and memcpy of its bytes (the memory's), and the scene's preparation.
//       N = 10^3 ... 10^7 (--quick: 10^3, 10^4).
//   big/ply/100000000/tall, big/ply-shadows/100000000/tall  (only with
//       --big): 10^8 spheres from a 1.5 GB PLY file (x y z floats, red green
//       blue; --radius 1), lit, 3840x2160, all cores, end to end as the
//       command line runs it (load, prepare, render), once, with the
//       process's peak memory. The file is written to $TMPDIR first (about
//       20 s) and removed after.
#pragma once

namespace raycast::bench {

void register_ply_rows(bool quick, bool big);

}  // namespace raycast::bench
