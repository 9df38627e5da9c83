// The book's own ch. 6 program logic as a peer (Ray Tracing in One Weekend
// v3.2.3, InOneWeekend/main.cc at the end of ch. 6): double precision, a
// virtual `hittable` interface, a `hittable_list` of shared_ptr, one ray per
// pixel, `int(255.999 c)`. Built with the project's -O3, no -march=native.
#pragma once
#include <memory>

#include "image/image.h"
#include "scene/scene.h"

namespace raycast::bench {

// Renders rows [band.row_begin, band.row_end) of the scene's image, 8-bit, the
// book's way (its spheres all normal-shaded; the book's world has no flat
// shading). Single-threaded, as the book's program.
class book_ch6 {
 public:
  explicit book_ch6(const scene& s);
  ~book_ch6();
  void render(const image_band& band) const;

 private:
  struct world;
  const scene& scene_;  // must outlive this
  std::unique_ptr<world> world_;
};

}  // namespace raycast::bench
