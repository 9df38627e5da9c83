#include "formats_rows.h"

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <charconv>
#include <ctime>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "formats/gsd/hoomd.h"
#include "formats/gsd_writer.h"
#include "formats/lammps/lammps_dump.h"
#include "rows.h"

namespace raycast::bench {
namespace {

using steady = std::chrono::steady_clock;
benchmark::Counter per_iteration(double v) { return {v, benchmark::Counter::kAvgIterations}; }

// The process's CPU seconds, all its threads (a .gz's read-ahead too).
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Wall and CPU seconds of the spans between start() and stop(), added up:
// on a machine shared with other work the CPU seconds are less swayed by it.
struct stopwatch {
  steady::time_point t0;
  double c0 = 0, wall = 0, cpu = 0;
  void start() {
    t0 = steady::now();
    c0 = cpu_now();
  }
  void stop() {
    wall += std::chrono::duration<double>(steady::now() - t0).count();
    cpu += cpu_now() - c0;
  }
  void report(benchmark::State& state) const {
    state.counters["seconds"] = per_iteration(wall);
    state.counters["cpu_seconds"] = per_iteration(cpu);
  }
};

std::string cache_dir() {
  const char* t = std::getenv("TMPDIR");
  const std::string d = std::string(t && t[0] == '/' ? t : "/tmp") + "/raycast-bench-formats";
  ::mkdir(d.c_str(), 0700);
  return d;
}

bool exists(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && st.st_size > 0;
}

double file_bytes(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? double(st.st_size) : 0.0;
}

// Reads the file once, so that the timed reads find it in the page cache.
void warm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buf(size_t(1) << 20);
  while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) {
  }
}

// v as LAMMPS's dump custom writes a float: printf's %g (six significant digits).
void put_g(std::string& s, double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, 6);
  s.append(b, r.ptr);
}

// An F-frame dump of n atoms a frame at LJ liquid density: id type x y z vx
// vy vz c_pe, as dump custom writes them, the same every run (seeded).
bool write_dump(const std::string& path, int frames, int64_t n) {
  const std::string tmp = path + ".part";
  std::ofstream out(tmp, std::ios::binary);
  const double side = std::cbrt(double(n) / 0.8442);
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> u(0.0, side);
  std::normal_distribution<double> g(0.0, 1.0);
  std::string s;
  for (int f = 0; f < frames && out; ++f) {
    char head[512];
    std::snprintf(head, sizeof head,
                  "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%lld\nITEM: BOX BOUNDS pp pp pp\n%-1.16e %-1.16e\n"
                  "%-1.16e %-1.16e\n%-1.16e %-1.16e\nITEM: ATOMS id type x y z vx vy vz c_pe\n",
                  1000 * f, static_cast<long long>(n), 0.0, side, 0.0, side, 0.0, side);
    out << head;
    for (int64_t k = 0; k < n && out; ++k) {
      s.clear();
      s += std::to_string(k + 1);
      s += rng() % 2 ? " 1" : " 2";
      for (int c = 0; c < 3; ++c) s += ' ', put_g(s, u(rng));
      for (int c = 0; c < 3; ++c) s += ' ', put_g(s, g(rng));
      s += ' ';
      put_g(s, -4.5 + 0.4 * g(rng));
      s += '\n';
      out << s;
    }
  }
  out.close();
  return out && std::rename(tmp.c_str(), path.c_str()) == 0;
}

bool gzip_file(const std::string& from, const std::string& to) {
  std::ifstream in(from, std::ios::binary);
  gzFile out = gzopen((to + ".part").c_str(), "wb6");
  if (!in || !out) return false;
  std::vector<char> buf(size_t(1) << 20);
  bool ok = true;
  while (ok && (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0))
    ok = gzwrite(out, buf.data(), unsigned(in.gcount())) == int(in.gcount());
  ok = gzclose(out) == Z_OK && ok;
  return ok && std::rename((to + ".part").c_str(), to.c_str()) == 0;
}

// A GSD frame of n particles: positions in a box, two types, diameters.
bool write_gsd_frame(const std::string& path, int64_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  const size_t count = static_cast<size_t>(n);
  std::vector<float> xyz(count * 3), diameter(count);
  std::vector<uint32_t> typeid_(count);
  for (float& v : xyz) v = u(rng);
  for (size_t k = 0; k < count; ++k) typeid_[k] = uint32_t(rng() % 2), diameter[k] = 1.0f + 0.001f * float(k % 100);
  const std::string bytes =
      raycast_test::write_gsd(raycast_test::hoomd_frame(0, xyz, typeid_, {"A", "B"}, diameter, {100, 100, 100, 0, 0, 0}));
  std::ofstream out(path + ".part", std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  return out && std::rename((path + ".part").c_str(), path.c_str()) == 0;
}

// The cached file of this name, written by make where it is missing; "" if it cannot be.
template <class Make>
std::string cached(const std::string& name, Make make) {
  const std::string path = cache_dir() + "/" + name;
  if (!exists(path) && !make(path)) return "";
  warm(path);
  return path;
}

}  // namespace

std::string dump_file(int frames, int64_t n) {
  return cached("dump-" + std::to_string(frames) + "x" + std::to_string(n) + ".lammpstrj",
                [&](const std::string& p) { return write_dump(p, frames, n); });
}

namespace {

std::string gz_file(int frames, int64_t n) {
  const std::string plain = dump_file(frames, n);
  return plain.empty() ? "" : cached("dump-" + std::to_string(frames) + "x" + std::to_string(n) + ".lammpstrj.gz",
                                     [&](const std::string& p) { return gzip_file(plain, p); });
}

formats::wanted_columns all_columns() {
  formats::wanted_columns w;
  w.all = true;
  return w;
}

// Open, read frame 0 with every column and count the frames (the scan
// goes on from where frame 0 ended): what a picture of the file's first
// frame costs. The text's MB/s.
void bench_ours(benchmark::State& state, std::string (*file)(int, int64_t), const formats::format* f, int64_t n,
                bool all) {
  const std::string path = file(1, n);
  if (path.empty()) return state.SkipWithError("cannot write the file in $TMPDIR/raycast-bench-formats");
  stopwatch w;
  size_t count = 0;
  for (auto _ : state) {
    w.start();
    try {
      auto traj = f->open(path);
      const particle_frame fr = traj->read(0, all ? all_columns() : formats::wanted_columns{});
      count = fr.count * traj->frame_count();  // the scan goes on from frame 0's end
      benchmark::DoNotOptimize(fr.positions.get(fr.count - 1, 2));
    } catch (const formats::format_error& e) {
      return state.SkipWithError(e.what());
    }
    w.stop();
  }
  if (count != size_t(n)) return state.SkipWithError("the frame is not the file's");
  const double bytes = path.ends_with(".gz") ? file_bytes(dump_file(1, n)) : file_bytes(path);
  w.report(state);
  state.counters["MBps"] = w.wall > 0 ? bytes * double(state.iterations()) / w.wall * 1e-6 : 0.0;
  state.counters["file_MB"] = file_bytes(path) * 1e-6;
}

// zlib alone on the .gz: inflated through a 256 KiB window that is dropped,
// the file read in 256 KiB blocks, as our reader reads it.
void bench_inflate(benchmark::State& state, int64_t n) {
  const std::string path = gz_file(1, n);
  if (path.empty()) return state.SkipWithError("cannot write the file in $TMPDIR/raycast-bench-formats");
  std::vector<unsigned char> in(size_t(1) << 18), out(size_t(1) << 18);
  stopwatch w;
  double text = 0;
  for (auto _ : state) {
    w.start();
    const int fd = ::open(path.c_str(), O_RDONLY);
    z_stream z{};
    inflateInit2(&z, 15 + 16);
    int r = Z_OK;
    text = 0;
    for (off_t at = 0; r != Z_STREAM_END;) {
      const ssize_t k = ::pread(fd, in.data(), in.size(), at);
      if (k <= 0) break;
      at += k;
      z.next_in = in.data();
      z.avail_in = uInt(k);
      while (z.avail_in > 0 && r != Z_STREAM_END) {
        z.next_out = out.data();
        z.avail_out = uInt(out.size());
        r = inflate(&z, Z_NO_FLUSH);
        if (r != Z_OK && r != Z_STREAM_END) break;
        text += double(out.size() - z.avail_out);
      }
    }
    inflateEnd(&z);
    ::close(fd);
    w.stop();
    if (r != Z_STREAM_END) return state.SkipWithError("zlib could not inflate the file");
  }
  w.report(state);
  state.counters["MBps"] = w.wall > 0 ? text * double(state.iterations()) / w.wall * 1e-6 : 0.0;
  state.counters["file_MB"] = file_bytes(path) * 1e-6;
}

// A peer in python3 on the same file, timed inside the process (its start
// and imports left out); "" where python3 or its module is missing.
void bench_python(benchmark::State& state, const std::string& peer, int64_t n) {
  const std::string path = dump_file(1, n);
  if (path.empty()) return state.SkipWithError("cannot write the file in $TMPDIR/raycast-bench-formats");
  const std::string load = peer == "numpy" ? "import numpy\nt, c = time.perf_counter(), time.process_time()\n"
                                             "a = numpy.loadtxt(p, skiprows=9)\nn = len(a)\n"
                                           : "import ase.io\nt, c = time.perf_counter(), time.process_time()\n"
                                             "a = ase.io.read(p, format='lammps-dump-text')\nn = len(a)\n";
  const std::string script = "import sys, time\np = sys.argv[1]\ntry:\n  exec(sys.argv[2])\nexcept ImportError as e:\n"
                             "  print('missing', e.name); sys.exit(0)\n"
                             "print(time.perf_counter() - t, time.process_time() - c, n)\n";
  const char* python = access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
  auto quote = [](const std::string& w) {
    std::string q = "'";
    for (char c : w) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string cmd = std::string(python) + " -c " + quote(script) + " " + quote(path) + " " + quote(load) + " 2>&1";
  std::string text;
  for (auto _ : state) {
    std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
    char buf[4096];
    text.clear();
    while (p && std::fgets(buf, sizeof buf, p.get())) text += buf;
  }
  double s = 0, cpu = 0;
  long long rows = 0;
  if (text.starts_with("missing") || std::sscanf(text.c_str(), "%lf %lf %lld", &s, &cpu, &rows) != 3 || rows != n)
    return state.SkipWithError(("python3 " + peer + ": " + text.substr(0, 160)).c_str());
  state.counters["seconds"] = s;
  state.counters["cpu_seconds"] = cpu;
  state.counters["MBps"] = file_bytes(path) / s * 1e-6;
}

void bench_gsd(benchmark::State& state, int64_t n) {
  const std::string path = cached("frame-" + std::to_string(n) + ".gsd", [&](const std::string& p) { return write_gsd_frame(p, n); });
  if (path.empty()) return state.SkipWithError("cannot write the file in $TMPDIR/raycast-bench-formats");
  stopwatch w;
  for (auto _ : state) {
    w.start();
    try {
      auto traj = formats::gsd_format().open(path);
      const particle_frame f = traj->read(0, {});
      benchmark::DoNotOptimize(f.radii->get(f.count - 1));
      if (f.count != size_t(n)) return state.SkipWithError("the frame is not the file's");
    } catch (const formats::format_error& e) {
      return state.SkipWithError(e.what());
    }
    w.stop();
  }
  const double chunks = double(n) * (12 + 4 + 4);  // position, typeid, diameter
  w.report(state);
  state.counters["MBps"] = w.wall > 0 ? chunks * double(state.iterations()) / w.wall * 1e-6 : 0.0;
}

// VmRSS and VmHWM of /proc/self/status, in bytes.
double status_bytes(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string k;
  double kb = 0;
  while (in >> k) {
    if (k == key && in >> kb) return kb * 1024.0;
    in.ignore(1 << 20, '\n');
  }
  return 0.0;
}

// Frames 0 .. frames-1 of a dump of `frames` frames, read in order, each
// dropped before the next: the cost a frame of a movie, and memory: the
// process's resident memory with each frame alive, sampled untimed (its
// largest, and how much it grew past the first frame's).
void bench_trajectory(benchmark::State& state, bool gz, int frames, int64_t n) {
  const std::string path = gz ? gz_file(frames, n) : dump_file(frames, n);
  if (path.empty()) return state.SkipWithError("cannot write the file in $TMPDIR/raycast-bench-formats");
  stopwatch w;
  double growth = 0, peak = 0;
  for (auto _ : state) {
    double first = 0;
    try {
      w.start();
      auto traj = formats::lammps_dump_format().open(path);
      for (int k = 0; k < frames; ++k) {
        const particle_frame f = traj->read(size_t(k), all_columns());
        benchmark::DoNotOptimize(f.positions.get(f.count - 1, 0));
        w.stop();
        const double rss = status_bytes("VmRSS:");  // with the frame alive (untimed)
        if (k == 0) first = rss;
        growth = std::max(growth, rss - first);
        peak = std::max(peak, rss);
        w.start();
      }
      w.stop();
    } catch (const formats::format_error& e) {
      return state.SkipWithError(e.what());
    }
  }
  w.report(state);
  state.counters["seconds_per_frame"] = per_iteration(w.wall / frames);
  state.counters["rss_growth_mb"] = growth * 1e-6;
  state.counters["peak_rss_mb"] = peak * 1e-6;
}

}  // namespace

void register_formats_rows(bool quick) {
  const int64_t n = quick ? 10000 : 1000000, m = quick ? 1000 : 100000;
  const std::string N = std::to_string(n), M = std::to_string(m);
  const auto fields = [](const std::string& family, const std::string& reader, int64_t atoms) {
    return "kind=formats family=" + family + " reader=" + reader + " atoms=" + std::to_string(atoms);
  };
  add_row("formats/lammps/" + N + "/ours", fields("lammps", "ours", n), benchmark::kMillisecond, bench_ours, dump_file,
          &formats::lammps_dump_format(), n, true);
  add_row("formats/lammps/" + N + "/ours-render", fields("lammps", "ours-render", n), benchmark::kMillisecond, bench_ours,
          dump_file, &formats::lammps_dump_format(), n, false);
  for (const char* peer : {"numpy", "ase"})
    add_row("formats/lammps/" + N + "/" + peer, fields("lammps", peer, n), benchmark::kMillisecond, bench_python,
            std::string(peer), n)
        ->Iterations(1);
  add_row("formats/lammps-gz/" + N + "/ours", fields("lammps-gz", "ours", n), benchmark::kMillisecond, bench_ours, gz_file,
          &formats::lammps_dump_format(), n, true);
  add_row("formats/lammps-gz/" + N + "/inflate", fields("lammps-gz", "inflate", n), benchmark::kMillisecond, bench_inflate, n);
  add_row("formats/gsd/" + N + "/ours", fields("gsd", "ours", n), benchmark::kMillisecond, bench_gsd, n);
  for (bool gz : {false, true})
    for (int frames : {1, 12})
      add_row("formats/trajectory/" + std::string(gz ? "lammps-gz/" : "lammps/") + M + "/" + std::to_string(frames),
              fields(gz ? "trajectory-gz" : "trajectory", "ours", m) + " frames=" + std::to_string(frames),
              benchmark::kMillisecond, bench_trajectory, gz, frames, m);
}

}  // namespace raycast::bench
