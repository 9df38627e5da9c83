// consumer OUT.ppm ARRAYS.ppm: the built-in "world" at 96 pixels wide with 4
// samples, once from the built-in scene with render_to_file, once from float
// arrays of the same spheres with render + write. Exit 0 when both worked and
// an out-of-range option is refused with the field named.
#include <raycast/raycast.h>

#include <cstdio>
#include <vector>

namespace rc = raycast::api;

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  rc::options o;
  o.samples = 4;
  rc::scene s = rc::builtin_scene("world");
  s.cam.width = 96;
  rc::render_to_file(s, o, argv[1]);

  const std::vector<float> centers = {0, 0, -1, 0, -100.5f, -1};
  const std::vector<float> radii = {0.5f, 100};
  rc::scene a;
  a.cam.width = 96;
  rc::sphere_arrays arr;
  arr.count = 2;
  arr.centers = rc::packed(centers.data(), 3);
  arr.radii = rc::packed(radii.data());
  a.arrays = arr;
  rc::write(argv[2], rc::render(a, o));

  try {
    o.threads = -1;
    rc::render(s, o);
    return 1;
  } catch (const rc::error& e) {
    if (e.field() != "threads" || e.kind() != rc::error::kind::invalid_argument) return 1;
  }
  std::puts("ok");
  return 0;
}
