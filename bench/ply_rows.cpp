#include "ply_rows.h"

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "cloud.h"
#include "errors.h"
#include "render/render.h"
#include "rows.h"
#include "formats/ply.h"

extern char** environ;

namespace raycast::bench {
namespace {

using steady = std::chrono::steady_clock;
double seconds_since(steady::time_point t0) { return std::chrono::duration<double>(steady::now() - t0).count(); }
benchmark::Counter per_iteration(double v) { return {v, benchmark::Counter::kAvgIterations}; }

std::string temp_dir() {
  const char* t = std::getenv("TMPDIR");
  return t && t[0] == '/' ? t : "/tmp";
}

// A temporary file of these bytes, removed with the object.
struct temp_file {
  std::string path;
  explicit temp_file(const std::string& suffix) {
    path = temp_dir() + "/raycast-bench-XXXXXX" + suffix;
    const int fd = mkstemps(path.data(), int(suffix.size()));
    if (fd < 0) path.clear();
    else ::close(fd);
  }
  ~temp_file() {
    if (!path.empty()) std::remove(path.c_str());
  }
};

const char* const ply_head = "ply\nformat binary_little_endian 1.0\nelement vertex %lld\nproperty float x\n"
                             "property float y\nproperty float z\nproperty float radius\nproperty uchar red\n"
                             "property uchar green\nproperty uchar blue\nend_header\n";

// The packed box's spheres as a PLY file: 19 bytes a sphere.
std::string box_ply(int64_t n) {
  const api::scene p = raycast_test::particle_box(n);
  std::string s = strf(ply_head, static_cast<long long>(n));
  s.reserve(s.size() + size_t(n) * 19);
  for (const sphere& b : p.spheres) {
    const float v[4] = {float(b.center.x), float(b.center.y), float(b.center.z), float(b.radius)};
    s.append(reinterpret_cast<const char*>(v), sizeof v);
    const unsigned char rgb[3] = {200, 120, 40};
    s.append(reinterpret_cast<const char*>(rgb), 3);
  }
  return s;
}

void bench_load_ply(benchmark::State& state, int64_t n) {
  const std::string bytes = box_ply(n);
  temp_file file(".ply");
  if (file.path.empty() || !(std::ofstream(file.path, std::ios::binary) << bytes)) {
    state.SkipWithError("cannot write a temporary file");
    return;
  }
  std::vector<char> copy(bytes.size());
  double load = 0, prep = 0, read = 0, mem = 0;
  for (auto _ : state) {
    const steady::time_point t0 = steady::now();
    auto got = read_ply_file(file.path, {});
    const double l = seconds_since(t0);
    auto* c = std::get_if<scene_file_contents>(&got);
    if (!c || !c->scene.arrays || c->scene.arrays->count != size_t(n)) {
      state.SkipWithError(c ? "the file's spheres are not the box's" : std::get<scene_file_error>(got).message.c_str());
      return;
    }
    c->scene.cam = raycast_test::particle_box(1).cam;
    const steady::time_point t1 = steady::now();
    auto r = std::make_unique<renderer>(raycast::make_scene(c->scene), render_options{});
    prep += seconds_since(t1);
    load += l;
    state.PauseTiming();
    r.reset();
    got = scene_file_error{};
    const steady::time_point t2 = steady::now();
    const int fd = ::open(file.path.c_str(), O_RDONLY);
    for (size_t at = 0; fd >= 0 && at < copy.size();) {
      const ssize_t k = ::pread(fd, copy.data() + at, copy.size() - at, off_t(at));
      if (k <= 0) break;
      at += size_t(k);
    }
    if (fd >= 0) ::close(fd);
    const steady::time_point t3 = steady::now();
    std::memcpy(copy.data(), bytes.data(), bytes.size());
    benchmark::ClobberMemory();
    mem += seconds_since(t3);
    read += std::chrono::duration<double>(t3 - t2).count();
    state.ResumeTiming();
  }
  const double per = 1e9 / double(n);
  state.counters["load_ns_per_sphere"] = per_iteration(load * per);
  state.counters["pread_ns_per_sphere"] = per_iteration(read * per);
  state.counters["memcpy_ns_per_sphere"] = per_iteration(mem * per);
  state.counters["prepare_ns_per_sphere"] = per_iteration(prep * per);
  state.counters["load_GBps"] = load > 0 ? double(bytes.size()) * double(state.iterations()) / load * 1e-9 : 0.0;
  state.counters["bytes_per_sphere"] = double(bytes.size()) / double(n);
}

// 10^8 spheres of radius 1 at packing fraction 0.3, uniform in a cube, as
// x y z floats and red green blue bytes (15 bytes a sphere), written a
// million at a time; the cube's side.
double write_big_box(const std::string& path, int64_t n) {
  const double side = std::cbrt(double(n) * 4.0 / 3.0 * M_PI / 0.3);
  std::ofstream out(path, std::ios::binary);
  out << strf("ply\nformat binary_little_endian 1.0\nelement vertex %lld\nproperty float x\nproperty float y\n"
              "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
              static_cast<long long>(n));
  std::mt19937 rng(5);
  std::vector<char> chunk;
  for (int64_t done = 0; done < n && out;) {
    const int64_t m = std::min<int64_t>(1000000, n - done);
    chunk.resize(size_t(m) * 15);
    for (int64_t k = 0; k < m; ++k) {
      float v[3];
      for (float& x : v) x = float(double(rng()) * 0x1p-32 * side);
      std::memcpy(chunk.data() + k * 15, v, sizeof v);
      const uint32_t c = uint32_t(rng());
      const unsigned char rgb[3] = {uint8_t(60 + c % 196), uint8_t(60 + (c >> 8) % 140), 90};
      std::memcpy(chunk.data() + k * 15 + 12, rgb, 3);
    }
    out.write(chunk.data(), std::streamsize(chunk.size()));
    done += m;
  }
  return out ? side : 0.0;
}

// A number after `label` in raycast --stats' text ("  prepare   1.23 s").
double stat(const std::string& text, const char* label) {
  const size_t at = text.find(label);
  return at == std::string::npos ? -1.0 : std::atof(text.c_str() + at + std::strlen(label));
}

// raycast (beside this program) on the file, its --stats read back.
std::string run_raycast(const std::vector<std::string>& args) {
  char self[4096];
  const ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
  const std::string exe = std::string(self, size_t(std::max<ssize_t>(k, 0)));
  // Each word in single quotes for the shell (a quote in it as '\'').
  const auto quoted = [](const std::string& w) {
    std::string q(1, '\'');
    for (char c : w) q.append(c == '\'' ? std::string("'\\''") : std::string(1, c));
    q.push_back('\'');
    return q;
  };
  std::string cmd = quoted(exe.substr(0, exe.find_last_of('/')) + "/raycast");
  for (const std::string& a : args) cmd.append(" ").append(quoted(a));
  cmd.append(" 2>&1");
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  std::string text;
  char buf[4096];
  while (p && std::fgets(buf, sizeof buf, p.get())) text += buf;
  return text;
}

// MemAvailable of /proc/meminfo in bytes (0 where unknown).
double memory_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  while (in >> key >> kb)
    if (key == "MemAvailable:") return kb * 1024.0;
  return 0.0;
}

void bench_big(benchmark::State& state, int64_t n, bool shadows) {
  // What a sphere costs (src/scene/README.md): the file's 15 bytes, the
  // primary rays' 85, shadows' 75; refused up front where it cannot fit.
  const double need = double(n) * (15 + 85 + (shadows ? 75 : 0)) * 1.1, have = memory_available();
  if (have > 0 && need > have) {
    state.SkipWithError(strf("needs about %.0f GB of memory; %.0f GB are available", need * 1e-9, have * 1e-9).c_str());
    return;
  }
  temp_file file(".ply"), image(".ppm");
  const steady::time_point w = steady::now();
  const double side = file.path.empty() ? 0.0 : write_big_box(file.path, n);
  if (!(side > 0)) {
    state.SkipWithError("cannot write the 10^8-sphere file to $TMPDIR");
    return;
  }
  state.counters["write_file_s"] = seconds_since(w);
  const std::string c = strf("%.6g,%.6g,%.6g", side / 2, side / 2, side / 2);
  const std::string from = strf("%.6g,%.6g,%.6g", 3.0 * side, 2.4 * side, 3.4 * side);
  std::vector<std::string> args = {"--scene", file.path, "--radius", "1", "--lookfrom", from, "--lookat", c,
                                   "--vfov", "30", "-w", "3840", "--height", "2160", "--stats", "-q", "-o", image.path};
  if (shadows) args.insert(args.end(), {"--light", "1,2,3", "--shadows"});
  std::string text;
  for (auto _ : state) text = run_raycast(args);
  if (stat(text, "total") < 0) {
    state.SkipWithError(("raycast failed: " + text.substr(0, 200)).c_str());
    return;
  }
  for (const char* k : {"load", "prepare", "render", "total"}) state.counters[std::string(k) + "_s"] = stat(text, k);
  state.counters["peak_rss_mb"] = stat(text, "peak RSS");
}

}  // namespace

void register_ply_rows(bool quick, bool big) {
  for (int64_t n : quick ? std::vector<int64_t>{1000, 10000} : std::vector<int64_t>{1000, 10000, 100000, 1000000, 10000000})
    add_row(strf("load-ply/%lld", static_cast<long long>(n)), strf("kind=load-ply spheres=%lld", static_cast<long long>(n)),
            benchmark::kMillisecond, bench_load_ply, n);
  if (!big) return;
  constexpr int64_t n = 100000000;
  for (bool shadows : {false, true})
    add_row(strf("big/%s/%lld/tall", shadows ? "ply-shadows" : "ply", static_cast<long long>(n)),
            strf("kind=big spheres=%lld shadows=%d size=3840x2160 threads=all", static_cast<long long>(n), int(shadows)),
            benchmark::kSecond, bench_big, n, shadows);
}

}  // namespace raycast::bench
