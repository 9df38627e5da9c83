#include "tachyon_peer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>

#include "image/image.h"
#include "render/render.h"

namespace raycast::bench {
namespace {

// Tachyon's camera for ours (tachyon_peer.h): its zoom and aspect ratio, the
// view direction turned by half a pixel, and the up direction.
struct tachyon_camera {
  double zoom = 1, aspect = 1;
  vec3 view{0.0}, up{0.0};
};

tachyon_camera camera_of(const camera& cam) {
  const int64_t W = cam.image_width, H = cam.image_height;
  const vec3 centre = cam.corner_dir + 0.5 * cam.horizontal + 0.5 * cam.vertical;
  const double dist = glm::length(centre);
  const double h = glm::length(cam.horizontal) / dist, g = glm::length(cam.vertical) / dist;  // at distance 1
  tachyon_camera t;
  t.zoom = double(H - 1) / (g * double(H));
  t.aspect = double(W - 1) * g / (double(H - 1) * h);
  // Tachyon's right is -u and its up v; its pixel x lies half a step right of ours.
  const vec3 right = -cam.axis_u, up = cam.axis_v;
  t.view = centre / dist - (h / (2.0 * double(W - 1))) * right - (g / (2.0 * double(H - 1))) * up;
  t.up = up;
  return t;
}

std::string temp_dir() {
  const char* t = std::getenv("TMPDIR");
  return t && *t ? t : "/tmp";
}

// The seconds after `label` in Tachyon's output, or -1.
double seconds_after(const std::string& out, const std::string& label) {
  const size_t at = out.find(label);
  if (at == std::string::npos) return -1;
  return std::strtod(out.c_str() + at + label.size(), nullptr);
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// A binary PPM (P6, maxval 255) as its width, height and bytes; empty where unreadable.
struct ppm {
  int64_t w = 0, h = 0;
  std::vector<unsigned char> px;
};
ppm read_ppm(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string magic;
  int maxval = 0;
  ppm p;
  if (!(f >> magic >> p.w >> p.h >> maxval) || magic != "P6" || maxval != 255) return {};
  f.get();
  p.px.resize(size_t(p.w * p.h) * 3);
  if (!f.read(reinterpret_cast<char*>(p.px.data()), std::streamsize(p.px.size()))) return {};
  return p;
}

}  // namespace

const std::string& tachyon_peer::program() {
  static const std::string found = [] {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(std::string(path ? path : "") + ":/usr/bin");
    for (std::string d; std::getline(dirs, d, ':');)
      if (!d.empty() && access((d + "/tachyon").c_str(), X_OK) == 0) return d + "/tachyon";
    return std::string();
  }();
  return found;
}

tachyon_peer::tachyon_peer(const scene& s) : s_(s) {
  std::string pattern = temp_dir() + "/raycast-tachyon-XXXXXX";
  if (mkdtemp(pattern.data())) dir_ = pattern;
}

tachyon_peer::~tachyon_peer() {
  if (dir_.empty()) return;
  for (int k = 0; k < files_; ++k) {
    std::remove((dir_ + "/scene" + std::to_string(k) + ".dat").c_str());
    std::remove((dir_ + "/out" + std::to_string(k) + ".ppm").c_str());
  }
  rmdir(dir_.c_str());
}

void tachyon_peer::write(const std::string& path, const scene& s, bool shadows, uint32_t ao) const {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return;
  const camera& cam = s.cam;
  const tachyon_camera t = camera_of(cam);
  std::fprintf(f, "BEGIN_SCENE\nRESOLUTION %lld %lld\nSHADER_MODE %s\n", static_cast<long long>(cam.image_width),
               static_cast<long long>(cam.image_height), shadows ? "FULL" : "MEDIUM");
  if (ao > 0) std::fprintf(f, "AMBIENT_OCCLUSION AMBIENT_COLOR 1 1 1 RESCALE_DIRECT 1.0 SAMPLES %u\n", ao);
  std::fprintf(f,
               "END_SHADER_MODE\nBACKGROUND 0 0 0\nCAMERA\n  ZOOM %.17g ASPECTRATIO %.17g ANTIALIASING 0 RAYDEPTH 1\n"
               "  CENTER %.17g %.17g %.17g\n  VIEWDIR %.17g %.17g %.17g\n  UPDIR %.17g %.17g %.17g\nEND_CAMERA\n",
               t.zoom, t.aspect, cam.origin.x, cam.origin.y, cam.origin.z, t.view.x, t.view.y, t.view.z, t.up.x,
               t.up.y, t.up.z);
  // DIRECTION: the way the light travels, away from it.
  const vec3 l = s.light.direction ? -unit_vector(to_glm(*s.light.direction)) : -cam.axis_w;
  std::fprintf(f, "DIRECTIONAL_LIGHT DIRECTION %.17g %.17g %.17g COLOR 1 1 1\n", l.x, l.y, l.z);
  // One texture: the bench's scenes colour every sphere alike (the first's).
  const api::vec3 c = s.sphere_count() > 0 ? s.sphere_at(0).color : api::vec3{1, 1, 1};
  std::fprintf(f, "TEXDEF lit AMBIENT %g DIFFUSE %g SPECULAR 0 OPACITY 1 COLOR %.9g %.9g %.9g TEXFUNC 0\n",
               double(lit_ambient), double(lit_diffuse), c.x, c.y, c.z);
  for (size_t k = 0; k < s.sphere_count(); ++k) {
    const sphere sp = s.sphere_at(k);
    std::fprintf(f, "SPHERE CENTER %.9g %.9g %.9g RAD %.9g lit\n", sp.center.x, sp.center.y, sp.center.z, sp.radius);
  }
  std::fputs("END_SCENE\n", f);
  std::fclose(f);
}

tachyon_peer::timers tachyon_peer::render(int threads, bool shadows, uint32_t ao, const std::string& out) const {
  timers t;
  if (program().empty()) return t.error = "no tachyon program (Debian: apt install tachyon)", t;
  if (dir_.empty()) return t.error = "no temporary directory for Tachyon's scene file", t;
  const std::string file = dir_ + "/scene" + std::to_string(files_) + ".dat";
  const std::string ppm = out.empty() ? dir_ + "/out" + std::to_string(files_) + ".ppm" : out;
  ++files_;
  write(file, s_, shadows, ao);
  const std::string cmd = quoted(program()) + " " + quoted(file) + " -numthreads " + std::to_string(threads) +
                          " -format PPM -o " + quoted(ppm) + " 2>&1";
  std::string text;
  if (std::FILE* p = popen(cmd.c_str(), "r")) {
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) text.append(buf, n);
    if (pclose(p) != 0) t.error = "tachyon failed: " + text.substr(0, 300);
  } else {
    t.error = "could not run " + program();
  }
  std::remove(file.c_str());
  t.preprocess = seconds_after(text, "Preprocessing Time:");
  t.trace = seconds_after(text, "Ray Tracing Time:");
  if (t.error.empty() && (t.preprocess < 0 || t.trace < 0)) t.error = "no timers in Tachyon's output: " + text.substr(0, 300);
  return t;
}

double tachyon_peer::framing_mismatch(int64_t w, int64_t h) const {
  scene small = s_;
  small.cam.image_width = w;  // the same viewport: pixel i at i / (w - 1) of it
  small.cam.image_height = h;
  small.sky = {color(0, 0, 0), color(0, 0, 0)};
  small.light = api::light{};
  for (sphere& sp : small.spheres) sp.shade = shading::flat, sp.color = api::vec3{1, 1, 1};
  const std::string ppm_path = dir_ + "/framing.ppm";
  const tachyon_peer peer(small);
  const timers t = peer.render(1, false, 0, ppm_path);
  const ppm theirs = read_ppm(ppm_path);
  std::remove(ppm_path.c_str());
  if (!t.error.empty() || theirs.w != w || theirs.h != h) return -1;
  render_options o;
  o.threads = 1;
  std::vector<unsigned char> ours(size_t(w * h) * 3);
  renderer(small, o).render({ours.data(), size_t(w) * 3, pixel_format::rgb8, 0, h});
  size_t differ = 0;
  for (int64_t row = 0; row < h; ++row)
    for (int64_t i = 0; i < w; ++i) {
      const unsigned char* a = &ours[size_t(row * w + i) * 3];
      const unsigned char* b = &theirs.px[size_t(row * w + (w - 1 - i)) * 3];
      differ += (a[0] | a[1] | a[2]) != 0 ? (b[0] | b[1] | b[2]) == 0 : (b[0] | b[1] | b[2]) != 0;
    }
  return double(differ) / double(w * h);
}

}  // namespace raycast::bench
