// raycast-bench: every way of computing the sky, timed with Google Benchmark,
// next to memset (the store-bandwidth bound) and with its error against the
// double reference, and the stiff cases' errors as rows of their own. Every
// run is also written as JSON, which bench/report.py turns into the summaries
// (error vs run time, peers, shortcuts, antialiasing, scale, stiff cases).
#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "aa_rows.h"
#include "cloud.h"
#include "embree_peer.h"
#include "embree_rows.h"
#include "errors.h"
#include "formats_rows.h"
#include "gbench_flags.h"
#include "rows.h"
#include "light_rows.h"
#include "ply_rows.h"
#include "scale_rows.h"
#include "trajectory_rows.h"
#include "spheres.h"
#include "sphere_numerics.h"

extern char** environ;

namespace raycast::bench {
namespace {

// Whether this program is the build tree's.
bool in_build_tree() { return exe_dir() == RAYCAST_BENCH_BUILD_BIN_DIR; }

// Where the aa/ rows' references are cached unless --aa-reference-dir says:
// the build tree's bench-cache for the raycast-bench built there, else (an
// installed one, which must not write into a build tree) the XDG cache,
// $XDG_CACHE_HOME/raycast or ~/.cache/raycast; '' (not cached) without either.
std::string default_cache_dir() {
  if (in_build_tree()) return RAYCAST_BENCH_CACHE_DIR;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && x[0] == '/') return std::string(x) + "/raycast";
  if (const char* h = std::getenv("HOME"); h && h[0] == '/') return std::string(h) + "/.cache/raycast";
  return "";
}

// bench/report.py: the source tree's for the build tree's raycast-bench, else
// the installed copy.
std::string report_script() { return in_build_tree() ? RAYCAST_BENCH_REPORT : RAYCAST_BENCH_REPORT_INSTALLED; }

struct options {
  bool quick = false;
  bool big = false;  // the 10^8-sphere rows
  std::string plot, summary_size;
  int summary_threads = 1;
  std::string aa_reference_dir = default_cache_dir();
  int64_t write_cloud = 0;  // > 0: print the particle cloud of that many spheres as a scene file
  std::string write_family = "cloud";  // which: cloud, dense, box, box-ortho or box-random (--write-<family>)
};

struct size2 {
  int64_t w, h;
};

const std::vector<path>& paths() {
  static const std::vector<path> all = available_paths();
  return all;
}

// Errors of every path at one size, measured the first time a row of that
// size asks (outside any timed loop), so each path and size costs one pass.
const error_stats& errors_for(size_t path_index, int64_t w, int64_t h) {
  static std::map<std::pair<int64_t, int64_t>, std::vector<error_stats>> cache;
  auto it = cache.find({w, h});
  if (it == cache.end())
    it = cache.emplace(std::pair{w, h}, measure_errors(make_scene(sized(w, h)), paths())).first;
  return it->second[path_index];
}

void bench_render(benchmark::State& state, size_t path_index, size2 size, int threads,
                  pixel_format format) {
  const error_stats& e = errors_for(path_index, size.w, size.h);
  const scene s = make_scene(sized(size.w, size.h));
  const painter paint(paths()[path_index], s, threads);
  const size_t stride = size_t(size.w) * bytes_per_pixel(format);
  const image_band band{scratch(stride * size_t(size.h)), stride, format, 0, size.h};
  time_pixels(state, double(size.w * size.h), [&] { paint.render(band); });
  state.counters["max_abs_err"] = e.max_abs_err;
  state.counters["rms_err"] = e.rms_err();
  state.counters["max_lsb"] = e.max_lsb;
  state.counters["lsb_mismatch"] = e.lsb_mismatch();
}

// The kernel allowed only some of the plan's shortcuts (render_options::shortcuts).
struct shortcut_set {
  const char* name;
  unsigned shortcuts;
};
const shortcut_set shortcut_sets[] = {
    {"none", shortcut::none},         {"lanes", shortcut::lanes},   {"lanes+mirror", shortcut::lanes | shortcut::mirror},
    {"channels", shortcut::channels}, {"clamps", shortcut::clamps}, {"all", shortcut::all},
};

void bench_shortcuts(benchmark::State& state, size_t path_index, size2 size, unsigned shortcuts) {
  const scene s = make_scene(sized(size.w, size.h));
  const painter paint(paths()[path_index], s, 1, shortcuts);
  const size_t stride = size_t(size.w) * 3;
  const image_band band{scratch(stride * size_t(size.h)), stride, pixel_format::rgb8, 0, size.h};
  time_pixels(state, double(size.w * size.h), [&] { paint.render(band); });
}

// shortcuts/BACKEND/PRECISION/WxH/t1/rgb8/SET: the SIMD backends at one size
// with each shortcut alone, none (the general path) and all (the default).
void register_shortcuts_rows(size2 sz) {
  for (size_t p = 0; p < paths().size(); ++p) {
    const path& pa = paths()[p];
    if (pa.autovec || pa.core == backend::reference || pa.core == backend::scalar) continue;
    const std::string prec(to_string(pa.prec)), size = size_text(sz.w, sz.h);
    for (const shortcut_set& v : shortcut_sets)
      add_row("shortcuts/" + pa.backend + "/" + prec + "/" + size + "/t1/rgb8/" + v.name,
              "kind=shortcuts backend=" + pa.backend + " precision=" + prec + " size=" + size +
                  " threads=1 out=rgb8 shortcuts=" + v.name,
              benchmark::kMicrosecond, bench_shortcuts, p, sz, v.shortcuts);
  }
}

void bench_memset(benchmark::State& state, size2 size) {
  const size_t bytes = size_t(size.w) * size_t(size.h) * 3;
  unsigned char* buf = scratch(bytes);
  time_pixels(state, double(size.w * size.h), [&] {
    std::memset(buf, 0x5a, bytes);
    benchmark::DoNotOptimize(buf);
  });
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes));
}

// bound/memset/WxH/rgb8 and render/BACKEND/PRECISION/WxH/tTHREADS/OUT.
void register_rows(const std::vector<size2>& sizes, const std::vector<int>& threads) {
  for (const size2& sz : sizes) {
    const std::string size = size_text(sz.w, sz.h);
    add_row("bound/memset/" + size + "/rgb8", "kind=bound backend=memset size=" + size + " out=rgb8",
            benchmark::kMicrosecond, bench_memset, sz);
    for (int t : threads)
      for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32})
        for (size_t p = 0; p < paths().size(); ++p) {
          const row_id r = render_row(paths()[p].backend, std::string(to_string(paths()[p].prec)), "", sz.w,
                                      sz.h, t, f == pixel_format::rgb8 ? "rgb8" : "f32");
          add_row(r.name, r.fields, benchmark::kMicrosecond, bench_render, p, sz, t, f);
        }
  }
}

// stiff/CASE/BACKEND/PRECISION (not timed: one iteration): a stiff sky case's
// error for one path, all paths measured by the case's first row.
void bench_stiff(benchmark::State& state, size_t case_index, size_t path_index) {
  static std::map<size_t, std::vector<error_stats>> cache;
  for (auto _ : state)
    if (!cache.count(case_index)) {
      const stiff_case c = stiff_cases()[case_index];
      cache[case_index] = measure_errors(make_scene(c.cam, c.sky), paths());
    }
  const error_stats& e = cache[case_index][path_index];
  state.counters["max_abs_err"] = e.max_abs_err;
  state.counters["max_lsb"] = e.max_lsb;
  state.counters["nan_count"] = double(e.nan_count);
}

// Embree's view of a scene as the metrics want it: rtcIntersect1's hits and
// the 8-bit image of the same single-ray path.
raycast_test::traced_image trace_embree(const scene& s, const embree_peer& peer) {
  raycast_test::traced_image t;
  t.width = s.cam.image_width;
  t.height = s.cam.image_height;
  t.rgb8.assign(size_t(t.width * t.height) * 3, 0);
  peer.render(image_band{t.rgb8.data(), size_t(t.width) * 3, pixel_format::rgb8, 0, t.height},
              embree_peer::mode::single);
  for (int64_t row = 0; row < t.height; ++row)
    for (int64_t i = 0; i < t.width; ++i) {
      const embree_peer::hit h = peer.trace(i, t.height - 1 - row);
      t.sphere.push_back(h.sphere);
      t.distance.push_back(h.distance);
    }
  return t;
}

// sphere_stiff/CASE/PEER (not timed: one iteration): a stiff sphere case
// (tests/support/sphere_numerics.h) against the double reference for ours
// (the scalar renderer, exact mode: every backend's bits), naive (the book's
// ch. 6 formula in float) or embree (rtcIntersect1).
void bench_sphere_stiff(benchmark::State& state, size_t case_index, std::string peer) {
  const raycast_test::sphere_stiff_case c = raycast_test::sphere_stiff_cases()[case_index];
  const scene s = raycast_test::scene_of(c);
  raycast_test::sphere_metrics m;
  for (auto _ : state) {
    const raycast_test::traced_image ref = raycast_test::trace_reference(s);
    if (peer == "embree") {
      const embree_peer e(s);
      if (!e.error().empty()) return state.SkipWithError(e.error().c_str());
      m = raycast_test::measure(ref, trace_embree(s, e));
    } else {
      m = raycast_test::measure(ref, peer == "ours" ? raycast_test::trace_ours(s) : raycast_test::trace_naive(s));
    }
  }
  const std::pair<const char*, double> counters[] = {
      {"wrong_object", m.wrong_object}, {"wrong_object_away", m.wrong_object_away},
      {"false_hits", m.false_hits},     {"false_hits_away", m.false_hits_away},
      {"false_misses", m.false_misses}, {"false_misses_away", m.false_misses_away},
      {"max_lsb", m.max_lsb},           {"max_lsb_away", m.max_lsb_away},
      {"max_rel_distance_err", m.max_rel_distance_err}};
  for (const auto& [k, v] : counters) state.counters[k] = v;
}

void register_stiff_rows() {
  const std::vector<stiff_case> cases = stiff_cases();
  for (size_t k = 0; k < cases.size(); ++k) {
    const api::camera& cam = cases[k].cam;
    const std::string fields = strf("kind=stiff case=%s index=%zu size=", cases[k].name.c_str(), k) +
                               size_text(cam.width, cam.height.value_or(
                                                              default_height(cam.width, cam.aspect)));
    if (auto why = validate(cam)) {  // refused: one row, its error the reason
      const std::string msg = why->message;
      add_row("stiff/" + cases[k].name, fields, benchmark::kMillisecond,
              [msg](benchmark::State& s) { s.SkipWithError(msg.c_str()); })
          ->Iterations(1);
      continue;
    }
    for (size_t p = 0; p < paths().size(); ++p) {
      const path& pa = paths()[p];
      if (!pa.autovec && pa.core == backend::reference) continue;  // the oracle
      const std::string prec(to_string(pa.prec));
      add_row("stiff/" + cases[k].name + "/" + pa.backend + "/" + prec,
              fields + " backend=" + pa.backend + " precision=" + prec, benchmark::kMillisecond, bench_stiff, k, p)
          ->Iterations(1);
    }
  }
  const std::vector<raycast_test::sphere_stiff_case> spheres = raycast_test::sphere_stiff_cases();
  for (size_t k = 0; k < spheres.size(); ++k) {
    const scene s = raycast_test::scene_of(spheres[k]);
    for (const std::string peer : {"ours", "naive", "embree"})
      add_row("sphere_stiff/" + spheres[k].name + "/" + peer,
              strf("kind=sphere_stiff case=%s index=%zu peer=%s size=", spheres[k].name.c_str(), k, peer.c_str()) +
                  size_text(s.cam.image_width, s.cam.image_height),
              benchmark::kMillisecond, bench_sphere_stiff, k, peer)
          ->Iterations(1);
  }
}

void print_help() {
  std::printf(
      "raycast-bench: time every sky renderer and compare it with the double reference\n"
      "  --quick                 seconds-long pass over 400x225 and 1920x1080\n"
      "  --big                   add the 10^8-sphere rows (big/: a 1.5 GB PLY file in\n"
      "                          $TMPDIR; 7.5 GB of memory, 15 GB with shadows; minutes)\n"
      "  --plot FILE.svg         write the error-vs-time scatter (and FILE-aa.svg,\n"
      "                          FILE-scale.svg) with matplotlib; .png works too\n"
      "  --summary-size WxH      size of the summary table (default 3840x2160;\n"
      "                          --quick: 1920x1080)\n"
      "  --summary-threads N     threads of the summary table (default 1)\n"
      "  --aa-reference-dir DIR  where the aa/ rows' converged references are cached\n"
      "                          (default %s; '' : not cached)\n"
      "  --write-cloud N         print the scale rows' particle cloud of N spheres as a\n"
      "                          scene file (for raycast --scene FILE --stats) and exit\n"
      "  --write-dense N, --write-box N, --write-box-ortho N, --write-box-random N\n"
      "                          the same for the dense cloud, the packed box, the box\n"
      "                          seen orthographically, and the box of random centres\n"
      "The summaries are %s's, from the run's JSON\n"
      "(python3 %s RUN.json --help). Google Benchmark's flags:\n",
      default_cache_dir().c_str(), report_script().c_str(), report_script().c_str());
  benchmark::PrintDefaultHelp();
}

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "raycast-bench: %s (see --help)\n", what.c_str());
  std::exit(2);
}

// Takes this program's flags out of argv; Google Benchmark's stay.
// The family of a --write-cloud, --write-dense or --write-box flag (with or
// without its =N), or null.
const char* write_flag(const char* arg) {
  for (const char* family : {"cloud", "dense", "box", "box-ortho", "box-random"}) {
    const std::string flag = std::string("--write-") + family;
    if (arg == flag || std::string(arg).rfind(flag + "=", 0) == 0) return family;
  }
  return nullptr;
}

options parse_own_flags(int& argc, char** argv) {
  options o;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const std::string& flag) -> std::optional<std::string> {
      if (arg == flag) {
        if (i + 1 >= argc) usage_error(flag + " needs a value");
        return std::string(argv[++i]);
      }
      if (arg.rfind(flag + "=", 0) == 0) return arg.substr(flag.size() + 1);
      return std::nullopt;
    };
    if (arg == "--quick") {
      o.quick = true;
    } else if (arg == "--big") {
      o.big = true;
    } else if (auto v = value("--plot")) {
      o.plot = *v;
    } else if (auto d = value("--aa-reference-dir")) {
      o.aa_reference_dir = *d;
    } else if (auto sz = value("--summary-size")) {
      long long w = 0, h = 0;
      char tail = 0;
      if (std::sscanf(sz->c_str(), "%lldx%lld%c", &w, &h, &tail) != 2 || w < 1 || h < 1)
        usage_error("--summary-size wants WxH, got '" + *sz + "'");
      o.summary_size = size_text(w, h);
    } else if (auto n = value("--summary-threads")) {
      char tail = 0;
      if (std::sscanf(n->c_str(), "%d%c", &o.summary_threads, &tail) != 1 || o.summary_threads < 1)
        usage_error("--summary-threads wants a positive integer, got '" + *n + "'");
    } else if (const char* family = write_flag(argv[i])) {
      const auto spheres = value(std::string("--write-") + family);
      long long count = 0;
      char tail = 0;
      if (!spheres || std::sscanf(spheres->c_str(), "%lld%c", &count, &tail) != 1 || count < 1 || count > 100000000)
        usage_error(std::string("--write-") + family + " wants a number of spheres from 1 to 10^8, got '" +
                    spheres.value_or("") + "'");
      o.write_cloud = count;
      o.write_family = family;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  argv[argc] = nullptr;
  return o;
}

// The display reporter, with every run also written to a JSON stream for the
// report (whatever --benchmark_out and --benchmark_format say).
class tee_json : public benchmark::BenchmarkReporter {
 public:
  tee_json(benchmark::BenchmarkReporter* display, std::ostream& json) : display_(display) {
    json_.SetOutputStream(&json);
    json_.SetErrorStream(&std::cerr);
  }
  bool ReportContext(const Context& context) override {
    display_->SetOutputStream(&GetOutputStream());
    display_->SetErrorStream(&GetErrorStream());
    json_.ReportContext(context);
    return display_->ReportContext(context);
  }
  void ReportRuns(const std::vector<Run>& runs) override {
    json_.ReportRuns(runs);
    display_->ReportRuns(runs);
  }
  void Finalize() override {
    json_.Finalize();
    display_->Finalize();
  }

 private:
  benchmark::BenchmarkReporter* display_;
  benchmark::JSONReporter json_;
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    const size_t colon = line.find(':');
    if (line.rfind("model name", 0) == 0 && colon != std::string::npos && colon + 2 <= line.size())
      return line.substr(colon + 2);
  }
  return "unknown CPU";
}

// What the report needs besides the rows, in the JSON's context.
void add_context(const options& opt) {
  benchmark::AddCustomContext("cpu_model", cpu_model());
  benchmark::AddCustomContext("pass", opt.quick ? "quick" : "full");  // the rows --quick registers, or all
  benchmark::AddCustomContext("available_cores", std::to_string(available_cores()));
  std::string skipped;
  for (const skipped_backend& s : skipped_backends())
    skipped += (skipped.empty() ? "" : "; ") + s.name + " (" + s.reason + ")";
  benchmark::AddCustomContext("skipped_backends", skipped.empty() ? "none (this CPU runs every backend)" : skipped);
  benchmark::AddCustomContext("summary_size", !opt.summary_size.empty() ? opt.summary_size
                                              : opt.quick              ? "1920x1080"
                                                                       : "3840x2160");
  benchmark::AddCustomContext("summary_threads", std::to_string(opt.summary_threads));
  benchmark::AddCustomContext("default_sampler", std::string(to_string(default_sampler)));
  benchmark::AddCustomContext("best_sphere_path", best_sphere_path().label());
  benchmark::AddCustomContext("aa_reference_dir", opt.aa_reference_dir);
}

// Runs the report script on the run's JSON, its output on stdout (tables on
// stderr when stdout is machine-readable); false when it could not run.
bool run_report(const std::string& json, const options& opt, bool to_stderr) {
  const char* env = std::getenv("RAYCAST_BENCH_PYTHON");
  const std::string python = env && *env ? env : access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
  std::vector<std::string> args = {python, report_script(), json};
  if (!opt.plot.empty()) args.insert(args.end(), {"--plot", opt.plot});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (to_stderr) posix_spawn_file_actions_adddup2(&fa, 2, 1);
  std::cout.flush();
  std::fflush(stdout);
  pid_t pid = 0;
  int status = 0;
  const bool ok = posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(), environ) == 0 &&
                  waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  posix_spawn_file_actions_destroy(&fa);
  return ok;
}

int run(int argc, char** argv) {
  const options opt = parse_own_flags(argc, argv);
  if (opt.write_cloud > 0) {
    const int64_t n = opt.write_cloud;
    const std::string text = raycast_test::cloud_json(
        opt.write_family == "box-ortho" ? raycast_test::particle_box(n, true)
        : opt.write_family == "box"     ? raycast_test::particle_box(n)
        : opt.write_family == "box-random" ? raycast_test::particle_box_random(n)
        : opt.write_family == "dense" ? raycast_test::particle_cloud(n, 3.0)
                                      : raycast_test::particle_cloud(n));
    const bool ok = std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0;
    if (!ok) std::perror("raycast-bench: --write-cloud");
    return ok ? 0 : 1;
  }
  // Google Benchmark's flags, with a short default min time (the library's
  // is 0.5 s): it keeps a full run's hundreds of rows short (the scale rows
  // are most of its minutes), and a row whose single iteration takes longer
  // (the reference and scalar rows at 15360x8640, the big scale rows) runs
  // exactly once, by the library's own rule, so timed rows' names stay free
  // of /iterations: suffixes (the untimed stiff rows, Iterations(1), carry
  // one). (Our default is set before Initialize, which replaces it only
  // when the command line gives --benchmark_min_time.) Rows may run in any
  // order (--benchmark_enable_random_interleaving): none needs another.
  benchmark::FLAGS_benchmark_min_time = opt.quick ? 0.02 : 0.1;
  benchmark::Initialize(&argc, argv, print_help);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  std::vector<size2> sizes = {{400, 225}, {1920, 1080}};
  if (!opt.quick) sizes.insert(sizes.end(), {{3840, 2160}, {15360, 8640}});
  std::vector<int> threads = {1};
  if (available_cores() > 1) threads.push_back(available_cores());
  register_rows(sizes, threads);
  register_shortcuts_rows(opt.quick ? size2{1920, 1080} : size2{3840, 2160});
  std::vector<std::pair<int64_t, int64_t>> scene_sizes;
  for (const size2& sz : sizes)
    if (sz.w <= 3840) scene_sizes.emplace_back(sz.w, sz.h);  // the reference at 15360x8640 takes minutes
  register_sphere_rows(scene_sizes, threads);
  register_aa_rows(aa_config_for(opt.quick, opt.aa_reference_dir));
  register_embree_rows(scene_sizes);
  register_scale_rows(opt.quick);
  register_ply_rows(opt.quick, opt.big);
  register_formats_rows(opt.quick);
  register_trajectory_rows(opt.quick);
  register_light_rows(opt.quick);
  register_stiff_rows();
  add_context(opt);

  char json[] = "/tmp/raycast-bench-XXXXXX.json";
  const int fd = mkstemps(json, 5);
  if (fd < 0) return std::perror("raycast-bench: temporary file"), 1;
  close(fd);
  {
    std::ofstream out(json);
    tee_json tee(benchmark::CreateDefaultDisplayReporter(), out);
    benchmark::RunSpecifiedBenchmarks(&tee);
    benchmark::Shutdown();
  }
  if (benchmark::FLAGS_benchmark_list_tests) return std::remove(json), 0;
  if (!run_report(json, opt, benchmark::FLAGS_benchmark_format != "console")) {
    std::fprintf(stderr,
                 "raycast-bench: no summary: `python3 %s %s` failed (it needs Python 3; --plot also "
                 "matplotlib, Debian python3-matplotlib); the rows stay in %s\n",
                 report_script().c_str(), json, json);
    return opt.plot.empty() ? 0 : 1;
  }
  std::remove(json);
  return 0;
}

}  // namespace
}  // namespace raycast::bench

int main(int argc, char** argv) { return raycast::bench::run(argc, argv); }
