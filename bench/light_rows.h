// raycast-bench's light section: lit particle scenes (tests/support/cloud.h's
// families, every sphere lit, a directional light) with hard shadows, and
// with shadows and 8 ambient-occlusion rays a hit (the packed box: AO
// distance 5 radii; the clouds: unbounded), 1920x1080, N = 10^4 .. 10^6
// (--quick: the box of 10^3 at 640x360). Per iteration:
//   light/FAMILY/ours/N/VARIANT/tT     the renderer's construction (the float
//       scene, the row index and the sphere grid: prepare_s) and one frame
//       (render_s); primary_s: the same frame without secondary rays (another
//       renderer, not in the row's time); 1 thread or all cores
//   light/FAMILY/embree/N/VARIANT/t1   the Embree peer's BVH (build_s), its
//       primary frame (primary_s), shadow rays (shadow_s) and AO rays (ao_s)
//       with rtcOccluded16; render_s is their sum
// rays_per_s: the frame's secondary rays over its secondary seconds
// (render_s - primary_s).
#pragma once

namespace raycast::bench {

void register_light_rows(bool quick);

}  // namespace raycast::bench
