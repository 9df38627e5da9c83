#include "stiff_cases.h"

namespace raycast_test {
namespace {

using namespace raycast;

api::camera scaled(double viewport_height, double focal_length) {
  api::camera p;
  p.viewport_height = viewport_height;
  p.focal_length = focal_length;
  return p;
}

api::camera at(double x, double y, double z) {
  api::camera p;
  p.lookfrom = point3(x, y, z);
  return p;
}

api::camera aspect(double ratio, int64_t w, std::optional<int64_t> h) {
  api::camera p;
  p.aspect = ratio;
  p.width = w;
  p.height = h;
  return p;
}

}  // namespace

std::vector<stiff_case> stiff_cases() {
  const sky lesson;
  sky hdr;
  hdr.bottom = color(4.0, 2.0, 0.5);
  hdr.top = color(-1.0, 0.25, 16.0);
  return {
      {"default 400x225", api::camera{}, lesson},
      {"W=1", sized(1, 225), lesson},
      {"H=1", sized(400, 1), lesson},
      {"W=H=1", sized(1, 1), lesson},
      {"aspect 100000:1", aspect(100000.0, 400, std::nullopt), lesson},
      {"aspect 1:100000", aspect(1e-5, 3, 300), lesson},
      {"scale 1e-30", scaled(2e-30, 1e-30), lesson},
      {"scale 1e30", scaled(2e30, 1e30), lesson},
      {"viewport 1e30 focal 1e-30", scaled(1e30, 1e-30), lesson},
      {"viewport 3e-38 focal 7e37", scaled(3e-38, 7e37), lesson},
      {"origin (1e8,-1e8,1e12)", at(1e8, -1e8, 1e12), lesson},
      {"origin +3.4e38", at(3.4e38, 3.4e38, 3.4e38), lesson},
      {"origin -3.4e38", at(-3.4e38, -3.4e38, -3.4e38), lesson},
      {"HDR sky (bottom 4,2,0.5 top -1,0.25,16)", api::camera{}, hdr},
  };
}

}  // namespace raycast_test
