// Embree 3 (Debian's libembree-dev) as a peer: the scene's spheres as one
// RTC_GEOMETRY_TYPE_SPHERE_POINT geometry (float4 x, y, z, r), primary rays
// traced with rtcIntersect16 (16 pixels of a row per packet, a valid mask for
// the row's tail) or rtcIntersect1, shaded and quantized as our float
// renderers do (kernels/float_spheres.h): the unit normal of the closest hit,
// facing the ray, 0.5 (N + 1), or the flat colour; the sky in float where
// nothing is hit; 8-bit int(clamp(c, 0, 1) * 255.999f). Single-threaded. Only
// the bench links Embree; the product does not.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "image/image.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace raycast::bench {

class embree_peer {
 public:
  enum class mode { packet16, single };

  // Builds the device (`threads=N`) and the committed scene (Embree's errors
  // are kept, not printed: see error()). s must outlive this.
  explicit embree_peer(const scene& s, int threads = 1);
  ~embree_peer();
  embree_peer(const embree_peer&) = delete;
  embree_peer& operator=(const embree_peer&) = delete;

  // Empty when the device and scene were built; otherwise Embree's message.
  const std::string& error() const;

  // Renders rows [band.row_begin, band.row_end), rgb8 or rgb_f32, on the
  // constructor's number of threads.
  void render(const image_band& band, mode m) const;

  // What the ray of pixel column i, row j (0 at the bottom) hits, traced with
  // rtcIntersect1 as render(single) traces it: the sphere's index (-1 for
  // none) and the distance tfar |d| from the camera, in world units (the
  // bench's stiff-sphere metrics, tests/support/sphere_numerics.h).
  struct hit {
    int64_t sphere = -1;
    double distance = 0.0;
  };
  hit trace(int64_t i, int64_t j) const;

  // Lit spheres under the scene's light (scene/light.h), rgb8: rtcIntersect16
  // for the primary rays (coherent), then rtcOccluded16 for the shadow rays
  // (coherent) and the ambient-occlusion rays (incoherent, 16 a packet), each
  // phase over the whole band before the next, on the constructor's threads.
  // The secondary rays are ours (light/secondary.h): from P = C + r n with
  // the same directions, but as an Embree user casts them: tnear = 2^-10 r,
  // since Embree cannot skip the sphere a ray leaves. Returns each phase's
  // seconds.
  struct light_seconds {
    double primary = 0, shadow = 0, ao = 0;
  };
  light_seconds render_lit(const image_band& band, const sampling::ao_plan& ao) const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

}  // namespace raycast::bench
