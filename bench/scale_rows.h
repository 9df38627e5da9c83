// raycast-bench's scale section: particle clouds (tests/support/cloud.h) of
// N = 1, 10, ..., 10^7 spheres at 1920x1080 (--quick: N = 1, 1000, 10^4), each row
// timing what a frame of a new scene costs, per iteration:
//   scale/ours/N/t1, scale/ours/N/tall     the renderer's construction (the
//       float scene, and the culling data once the constructor builds it:
//       counter prepare_s) and one frame (render_s), default backend and
//       precision, 1 thread or all cores
//   scale/embree/N/t1, scale/embree/N/tall the Embree peer's construction
//       (device and BVH: build_s) and one rtcIntersect16 frame (render_s)
//   load/N  parse_scene_file of the cloud's JSON text (in memory) and the
//       scene's preparation (make_scene and the renderer), per sphere
// The row's time is prepare + render (freeing the scene is not in it). From
// N = 10^5 an iteration outlasts the bench's default min time, so those rows
// run one iteration (main.cpp's rule; repetitions come from the command
// line). A full run of these rows peaks at about 8 GB (load/10^7: the JSON
// text and the parser's tree).
#pragma once

namespace raycast::bench {

void register_scale_rows(bool quick);

}  // namespace raycast::bench
