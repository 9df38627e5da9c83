// Particle files for the tests: random particles written as PLY (ASCII,
// little- or big-endian binary) and as the JSON scene of the same spheres.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace raycast_test {

struct particle {
  float x, y, z, radius;
  uint8_t rgb[3];
  int32_t id;
};

inline std::vector<particle> random_particles(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-2.0f, 2.0f), rad(0.05f, 0.4f);
  std::vector<particle> v(n);
  for (size_t k = 0; k < n; ++k) {
    v[k] = {pos(rng), pos(rng), pos(rng) - 5.0f, rad(rng), {}, int32_t(k)};
    for (uint8_t& c : v[k].rgb) c = uint8_t(rng() & 0xff);
  }
  return v;
}

enum class enc { ascii, little, big };
constexpr const char* format_names[] = {"ascii", "binary_little_endian", "binary_big_endian"};

template <class T>
void put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof v);
  if (big) std::reverse(b, b + sizeof b);
  out.append(b, sizeof b);
}

// A PLY file of the particles: x y z [radius] [red green blue] id.
inline std::string ply_of(const std::vector<particle>& ps, enc e, bool radius = true, bool colors = true,
                   const std::string& before_vertex = "") {
  std::string s = std::string("ply\nformat ") + format_names[int(e)] + " 1.0\ncomment made by test_ply\n" +
                  before_vertex + "element vertex " + std::to_string(ps.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\n";
  if (radius) s += "property float radius\n";
  if (colors) s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  s += "property int id\nend_header\n";
  for (const particle& p : ps) {
    if (e == enc::ascii) {
      char line[160];
      int n = std::snprintf(line, sizeof line, "%.9g %.9g %.9g", p.x, p.y, p.z);
      if (radius) n += std::snprintf(line + n, sizeof line - size_t(n), " %.9g", p.radius);
      if (colors) n += std::snprintf(line + n, sizeof line - size_t(n), " %d %d %d", p.rgb[0], p.rgb[1], p.rgb[2]);
      std::snprintf(line + n, sizeof line - size_t(n), " %d\n", p.id);
      s += line;
      continue;
    }
    const bool big = e == enc::big;
    for (float f : {p.x, p.y, p.z}) put(s, f, big);
    if (radius) put(s, p.radius, big);
    if (colors) s.append(reinterpret_cast<const char*>(p.rgb), 3);
    put(s, p.id, big);
  }
  return s;
}

// The JSON scene of the same spheres, lit in their colours (as a PLY file's).
inline std::string json_of(const std::vector<particle>& ps) {
  std::string s = "{\"spheres\": [";
  char buf[256];
  for (size_t k = 0; k < ps.size(); ++k) {
    const particle& p = ps[k];
    std::snprintf(buf, sizeof buf, "%s{\"center\": [%.17g, %.17g, %.17g], \"radius\": %.17g, \"shade\": \"lit\", "
                  "\"color\": [%.17g, %.17g, %.17g]}", k ? ", " : "", double(p.x), double(p.y), double(p.z),
                  double(p.radius), p.rgb[0] / 255.0, p.rgb[1] / 255.0, p.rgb[2] / 255.0);
    s += buf;
  }
  return s + "]}";
}

}  // namespace raycast_test
