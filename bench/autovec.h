// The autovec peer: the lesson's loop in float, written the way a user would,
// compiled alone with -O3 -march=native -ffast-math (bench/CMakeLists.txt).
// Only plain data crosses this header: no inline code compiled for the native
// instruction set can leak into the rest of the program.
#pragma once
#include <cstddef>
#include <cstdint>

namespace raycast::bench {

struct autovec_camera {
  int64_t width = 0, height = 0;
  float origin[3] = {};
  float viewport_width = 0, viewport_height = 0, focal_length = 0;
  float bottom[3] = {}, top[3] = {};  // sky colours at t = 0 and t = 1
};

// Rows [r0, r1) (row 0 at the top) into data, whose row r0 starts at data;
// interleaved RGB8 (the lesson's int(255.999 c), unclamped) or float RGB.
// threads > 1 splits the rows with `#pragma omp parallel for`.
void autovec_render_rows(const autovec_camera& cam, bool f32, void* data, size_t stride, int64_t r0,
                         int64_t r1, int threads);

}  // namespace raycast::bench
