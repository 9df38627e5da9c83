// raycast-bench's light section: lit particle scenes (tests/support/cloud.h's
// families, every sphere lit, a directional light) with hard shadows, and
// with shadows and 8 ambient-occlusion rays a hit (the packed boxes: AO
// distance 5 radii, and unbounded in the variant shadows-ao8-unbounded; the
// clouds: unbounded), 1920x1080, N = 10^4 .. 10^7 (--quick: the box of 10^3
// at 640x360). Per iteration:
//   light/FAMILY/ours/N/VARIANT/tT     the renderer's construction (the float
//       scene, the row index and the sphere grid: prepare_s) and one frame
//       (render_s); primary_s: the same frame without secondary rays (another
//       renderer, not in the row's time); light_s: the far field's build (of
//       prepare_s); lists, lists_s and light_mb: the spheres whose near-field
//       lists the frame gathered, the threads' seconds gathering them (of
//       render_s), and the light's megabytes after it; 1 thread or all cores
//   light/FAMILY/embree/N/VARIANT/t1   the Embree peer's BVH (build_s), its
//       primary frame (primary_s), shadow rays (shadow_s) and AO rays (ao_s)
//       with rtcOccluded16; render_s is their sum
//   light/FAMILY/tachyon/N/VARIANT/tT  Tachyon (bench/tachyon_peer.h) on the
//       same scene file's camera, light and spheres, the same rays a hit,
//       where its AO is ours (unbounded, or none), N <= 10^6: its own
//       preprocessing (prepare_s) and ray tracing (render_s) timers, 1 thread
//       or all cores; frame_mismatch, the fraction of pixels whose hit differs
//       between its picture and ours. Skipped, saying so, without tachyon.
// And ambient occlusion's error against run time:
//   ao/SAMPLER/box2000/WxH/aoN   a lit box of 2000 spheres, AO distance 5
//       radii, N = 1, 2, 4, ..., 256 rays a hit (--quick: 1, 4, 16), one
//       sample a pixel, rgb_f32, one thread; rms_err and max_abs_err of its
//       linear colour against the same scene at 4096 sobol rays a hit
//       (--quick: 256), 320x180 (--quick: 160x90)
#pragma once

namespace raycast::bench {

void register_light_rows(bool quick);

}  // namespace raycast::bench
