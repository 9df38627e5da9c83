// Tachyon (Debian's `tachyon`, the scalar ray tracer OVITO and VMD ship, over a
// hierarchical uniform grid) as a peer of the light rows: our scene written as
// a Tachyon scene file (.dat: camera, one directional light, every sphere with
// the lit spheres' texture, AMBIENT 0.2 DIFFUSE 0.8 as scene/sphere.h's
// lit_ambient and lit_diffuse), rendered by the program itself, its own
// "Preprocessing Time" and "Ray Tracing Time" read from what it prints.
//
// The camera: Tachyon's image plane lies at distance 1 along VIEWDIR, 1 / ZOOM
// high, its pixel x (1 to W) at x / W of its width from the left edge, and its
// right is UPDIR x VIEWDIR, our left: its picture is ours mirrored in x. The
// zoom and aspect ratio are chosen so that its pixels are spaced as ours
// (scene/camera.h: pixel i at i / (W - 1) of the viewport), and VIEWDIR is
// turned by half a pixel so that they fall on our pixels' points (checked by
// framing_mismatch). Shadows: SHADER_MODE FULL (one shadow ray a hit toward
// the light); none: MEDIUM. Ambient occlusion: AMBIENT_OCCLUSION ... SAMPLES
// N, unbounded (Tachyon has no distance for it). Only the bench runs it.
#pragma once
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace raycast::bench {

class tachyon_peer {
 public:
  // The tachyon program found on PATH (or /usr/bin/tachyon), or empty.
  static const std::string& program();

  // Tachyon's timers of one frame, seconds; error: why it did not run.
  struct timers {
    double preprocess = 0, trace = 0;
    std::string error;
  };

  // The scene's files go to $TMPDIR (else /tmp), removed by the destructor.
  explicit tachyon_peer(const scene& s);
  ~tachyon_peer();
  tachyon_peer(const tachyon_peer&) = delete;
  tachyon_peer& operator=(const tachyon_peer&) = delete;

  // One frame of the scene's camera and spheres, with shadows or not and ao
  // rays a hit, on `threads` threads; the picture as PPM to ppm if not empty.
  timers render(int threads, bool shadows, uint32_t ao, const std::string& ppm = "") const;

  // Whether both pictures show the same spheres in the same places: the
  // scene's spheres at w x h, Tachyon's hit pixels (MEDIUM, no AO, a black
  // background: every hit has colour) against ours (the same camera, every
  // sphere flat white under a black sky), Tachyon's mirrored back. The
  // fraction of pixels that hit in one picture and not in the other (only
  // rays that graze a sphere's edge can differ); negative where Tachyon did
  // not run.
  double framing_mismatch(int64_t w, int64_t h) const;

 private:
  void write(const std::string& path, const scene& s, bool shadows, uint32_t ao) const;

  const scene& s_;
  std::string dir_;
  mutable int files_ = 0;
};

}  // namespace raycast::bench
