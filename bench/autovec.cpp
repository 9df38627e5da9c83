// The lesson's loop as a user would port it to float and let the compiler
// vectorize it: no explicit SIMD, no care for edge cases (W = 1 divides by
// zero, far origins cancel, 8-bit values above 1 wrap). Built with
// -O3 -march=native -ffast-math; everything here has internal linkage.
#include "autovec.h"

#include <cmath>

namespace raycast::bench {
namespace {

struct vec3 {
  float x, y, z;
};
vec3 operator+(vec3 a, vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
vec3 operator-(vec3 a, vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
vec3 operator*(float s, vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
vec3 operator/(vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
float length(vec3 a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
vec3 unit_vector(vec3 a) { return a / length(a); }

template <bool F32>
void render(const autovec_camera& cam, unsigned char* data, size_t stride, int64_t r0, int64_t r1,
            int threads) {
  const int64_t W = cam.width, H = cam.height;
  const vec3 origin{cam.origin[0], cam.origin[1], cam.origin[2]};
  const vec3 horizontal{cam.viewport_width, 0.0f, 0.0f};
  const vec3 vertical{0.0f, cam.viewport_height, 0.0f};
  const vec3 lower_left_corner =
      origin - 0.5f * horizontal - 0.5f * vertical - vec3{0.0f, 0.0f, cam.focal_length};
  const vec3 bottom{cam.bottom[0], cam.bottom[1], cam.bottom[2]};
  const vec3 top{cam.top[0], cam.top[1], cam.top[2]};

#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = H - 1 - r;
    unsigned char* row = data + size_t(r - r0) * stride;
    float* rowf = reinterpret_cast<float*>(row);
    for (int64_t i = 0; i < W; ++i) {
      const float u = float(i) / float(W - 1);
      const float v = float(j) / float(H - 1);
      const vec3 direction = lower_left_corner + u * horizontal + v * vertical - origin;
      const vec3 unit = unit_vector(direction);
      const float t = 0.5f * (unit.y + 1.0f);
      const vec3 c = (1.0f - t) * bottom + t * top;
      if constexpr (F32) {
        rowf[3 * i + 0] = c.x;
        rowf[3 * i + 1] = c.y;
        rowf[3 * i + 2] = c.z;
      } else {
        row[3 * i + 0] = static_cast<unsigned char>(static_cast<int>(255.999f * c.x));
        row[3 * i + 1] = static_cast<unsigned char>(static_cast<int>(255.999f * c.y));
        row[3 * i + 2] = static_cast<unsigned char>(static_cast<int>(255.999f * c.z));
      }
    }
  }
}

}  // namespace

void autovec_render_rows(const autovec_camera& cam, bool f32, void* data, size_t stride, int64_t r0,
                         int64_t r1, int threads) {
  auto* bytes = static_cast<unsigned char*>(data);
  if (f32)
    render<true>(cam, bytes, stride, r0, r1, threads);
  else
    render<false>(cam, bytes, stride, r0, r1, threads);
}

}  // namespace raycast::bench
