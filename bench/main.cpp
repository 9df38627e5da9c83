// raycast-bench: every way of computing the sky, timed with Google Benchmark,
// next to memset (the store-bandwidth bound) and with its error against the
// double reference; then an error-vs-run-time summary and the stiff cases.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "aa_report.h"
#include "aa_rows.h"
#include "embree_peer.h"
#include "embree_rows.h"
#include "errors.h"
#include "gbench_flags.h"
#include "report.h"
#include "scale_rows.h"
#include "spheres.h"
#include "sphere_numerics.h"

namespace raycast::bench {
namespace {

// Where the aa/ rows' references are cached unless --aa-reference-dir says:
// the build tree's bench-cache for the raycast-bench built there, else (an
// installed one, which must not write into a build tree) the XDG cache,
// $XDG_CACHE_HOME/raycast or ~/.cache/raycast; '' (not cached) without either.
std::string default_cache_dir() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) {
    const std::string exe(buf, size_t(n));
    if (exe.substr(0, exe.find_last_of('/')) == RAYCAST_BENCH_BUILD_BIN_DIR) return RAYCAST_BENCH_CACHE_DIR;
  }
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && x[0] == '/') return std::string(x) + "/raycast";
  if (const char* h = std::getenv("HOME"); h && h[0] == '/') return std::string(h) + "/.cache/raycast";
  return "";
}

struct options {
  bool quick = false;
  std::string plot;
  std::optional<std::pair<int64_t, int64_t>> summary_size;
  int summary_threads = 1;
  std::string aa_reference_dir = default_cache_dir();
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
  for (auto _ : state) {
    paint.render(band);
    benchmark::ClobberMemory();
  }
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
const std::vector<shortcut_set>& shortcut_sets() {
  static const std::vector<shortcut_set> v = {
      {"none", shortcut::none},
      {"lanes", shortcut::lanes},
      {"lanes+mirror", shortcut::lanes | shortcut::mirror},
      {"channels", shortcut::channels},
      {"clamps", shortcut::clamps},
      {"all", shortcut::all},
  };
  return v;
}

void bench_shortcuts(benchmark::State& state, size_t path_index, size2 size, unsigned shortcuts) {
  const scene s = make_scene(sized(size.w, size.h));
  const painter paint(paths()[path_index], s, 1, shortcuts);
  const size_t stride = size_t(size.w) * 3;
  const image_band band{scratch(stride * size_t(size.h)), stride, pixel_format::rgb8, 0, size.h};
  for (auto _ : state) {
    paint.render(band);
    benchmark::ClobberMemory();
  }
}

// shortcuts/ rows: the SIMD backends at one size with each shortcut alone, the
// general path (none) first so the others can report vs_none.
void register_shortcuts_rows(size2 sz) {
  for (size_t p = 0; p < paths().size(); ++p) {
    const path& pa = paths()[p];
    if (pa.autovec || pa.core == backend::reference || pa.core == backend::scalar) continue;
    for (const shortcut_set& v : shortcut_sets())
      benchmark::RegisterBenchmark(
          shortcuts_row_name(pa.backend, to_string(pa.prec), sz.w, sz.h, v.name).c_str(),
          bench_shortcuts, p, sz, v.shortcuts)
          ->Unit(benchmark::kMicrosecond);
  }
}

void bench_memset(benchmark::State& state, size2 size) {
  const size_t bytes = size_t(size.w) * size_t(size.h) * 3;
  unsigned char* buf = scratch(bytes);
  for (auto _ : state) {
    std::memset(buf, 0x5a, bytes);
    benchmark::DoNotOptimize(buf);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes));
}

// Rows grouped by size, threads and output, memset and the reference first:
// the reporter needs their times for the other rows' speedup and vs_memset.
void register_rows(const std::vector<size2>& sizes, const std::vector<int>& threads) {
  for (const size2& sz : sizes) {
    benchmark::RegisterBenchmark(memset_row_name(sz.w, sz.h).c_str(), bench_memset, sz)
        ->Unit(benchmark::kMicrosecond);
    for (int t : threads)
      for (pixel_format f : {pixel_format::rgb8, pixel_format::rgb_f32})
        for (size_t p = 0; p < paths().size(); ++p) {
          const std::string name =
              render_row_name(paths()[p].backend, to_string(paths()[p].prec), sz.w, sz.h, t,
                              f == pixel_format::rgb8 ? "rgb8" : "f32");
          benchmark::RegisterBenchmark(name.c_str(), bench_render, p, sz, t, f)
              ->Unit(benchmark::kMicrosecond);
        }
  }
}

void print_help() {
  std::printf(
      "raycast-bench: time every sky renderer and compare it with the double reference\n"
      "  --quick                 seconds-long pass over 400x225 and 1920x1080\n"
      "  --plot FILE.svg         write the error-vs-time scatter as SVG\n"
      "  --summary-size WxH      size of the summary table (default 3840x2160;\n"
      "                          --quick: 1920x1080)\n"
      "  --summary-threads N     threads of the summary table (default 1)\n"
      "  --aa-reference-dir DIR  where the aa/ rows' converged references are cached\n"
      "                          (default %s; '' : not cached)\n"
      "Google Benchmark's flags:\n",
      default_cache_dir().c_str());
  benchmark::PrintDefaultHelp();
}

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "raycast-bench: %s (see --help)\n", what.c_str());
  std::exit(2);
}

// Takes this program's flags out of argv; Google Benchmark's stay.
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
    } else if (auto v = value("--plot")) {
      o.plot = *v;
    } else if (auto d = value("--aa-reference-dir")) {
      o.aa_reference_dir = *d;
    } else if (auto sz = value("--summary-size")) {
      long long w = 0, h = 0;
      char tail = 0;
      if (std::sscanf(sz->c_str(), "%lldx%lld%c", &w, &h, &tail) != 2 || w < 1 || h < 1)
        usage_error("--summary-size wants WxH, got '" + *sz + "'");
      o.summary_size = std::pair<int64_t, int64_t>(w, h);
    } else if (auto n = value("--summary-threads")) {
      char tail = 0;
      if (std::sscanf(n->c_str(), "%d%c", &o.summary_threads, &tail) != 1 || o.summary_threads < 1)
        usage_error("--summary-threads wants a positive integer, got '" + *n + "'");
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  argv[argc] = nullptr;
  return o;
}

std::unique_ptr<benchmark::BenchmarkReporter> make_file_reporter(const std::string& format) {
  if (format == "console")
    return std::make_unique<benchmark::ConsoleReporter>(benchmark::ConsoleReporter::OO_None);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  if (format == "csv") return std::make_unique<benchmark::CSVReporter>();
#pragma GCC diagnostic pop
  return std::make_unique<benchmark::JSONReporter>();
}

std::vector<stiff_result> run_stiff_cases() {
  std::vector<stiff_result> results;
  for (const stiff_case& c : stiff_cases()) {
    stiff_result r;
    r.name = c.name;
    r.width = c.cam.image_width;
    r.height = c.cam.image_height.value_or(default_height(c.cam.image_width, c.cam.aspect_ratio));
    if (auto why = validate(c.cam))
      r.invalid = why->message;
    else
      r.errors = measure_errors(make_scene(c.cam, c.sky), paths());
    results.push_back(std::move(r));
  }
  return results;
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

std::vector<sphere_stiff_result> run_sphere_stiff_cases() {
  std::vector<sphere_stiff_result> results;
  for (const raycast_test::sphere_stiff_case& c : raycast_test::sphere_stiff_cases()) {
    const scene s = raycast_test::scene_of(c);
    const raycast_test::traced_image ref = raycast_test::trace_reference(s);
    sphere_stiff_result r;
    r.name = c.name;
    r.width = s.cam.image_width;
    r.height = s.cam.image_height;
    r.ours = raycast_test::measure(ref, raycast_test::trace_ours(s));
    r.naive = raycast_test::measure(ref, raycast_test::trace_naive(s));
    const embree_peer peer(s);
    r.embree_error = peer.error();
    if (r.embree_error.empty()) r.embree = raycast_test::measure(ref, trace_embree(s, peer));
    results.push_back(std::move(r));
  }
  return results;
}

// Google Benchmark's flags, with a short default min time: it keeps the full
// run within two minutes, and a row whose single iteration takes longer (the
// reference and scalar rows at 15360x8640) runs exactly once, by the
// library's own rule, so row names stay free of /iterations: suffixes.
// (Our default is set before Initialize, which replaces it only when the
// command line gives --benchmark_min_time.) Rows run in registration order:
// a row's speedup and vs_memset are filled from rows reported before it, so
// the library's --benchmark_enable_random_interleaving, which shuffles them,
// leaves those counters out where it puts a row before its yardstick (the
// summaries, read at the end, are whole either way; README "Antialiasing").
void init_benchmark(int& argc, char** argv, bool quick) {
  benchmark::FLAGS_benchmark_min_time = quick ? 0.02 : 0.1;
  benchmark::Initialize(&argc, argv, print_help);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) std::exit(2);
}

// Runs the registered rows through reporters that fill the cross-row counters.
void run_rows(run_table& table) {
  counter_filler display(benchmark::CreateDefaultDisplayReporter(), table);
  std::unique_ptr<benchmark::BenchmarkReporter> file_inner;
  std::unique_ptr<counter_filler> file;
  if (!benchmark::FLAGS_benchmark_out.empty()) {
    file_inner = make_file_reporter(benchmark::FLAGS_benchmark_out_format);
    file = std::make_unique<counter_filler>(file_inner.get(), table);
  }
  benchmark::RunSpecifiedBenchmarks(&display, file.get());
  benchmark::Shutdown();
}

int run(int argc, char** argv) {
  const options opt = parse_own_flags(argc, argv);
  init_benchmark(argc, argv, opt.quick);
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
  const aa_config aa = aa_config_for(opt.quick, opt.aa_reference_dir);
  register_aa_rows(aa);
  register_embree_rows(scene_sizes);
  register_scale_rows(opt.quick);

  run_table table;
  run_rows(table);
  if (benchmark::FLAGS_benchmark_list_tests) return 0;

  // Machine-readable stdout stays machine-readable: the tables go to stderr.
  const std::string format = benchmark::FLAGS_benchmark_format;
  std::ostream& os = format == "console" ? std::cout : std::cerr;
  summary_options so;
  const std::pair<int64_t, int64_t> size =
      opt.summary_size.value_or(opt.quick ? std::pair<int64_t, int64_t>{1920, 1080}
                                          : std::pair<int64_t, int64_t>{3840, 2160});
  so.width = size.first;
  so.height = size.second;
  so.threads = opt.summary_threads;
  so.cpu = cpu_model();
  so.date = today();
  const std::vector<summary_row> rows = summary_rows(table, so);
  print_summary(os, rows, so, skipped_backends());
  if (!opt.plot.empty()) {
    if (!write_svg(opt.plot, rows, so)) {
      std::fprintf(stderr, "raycast-bench: cannot write %s\n", opt.plot.c_str());
      return 1;
    }
    os << "Plot written to " << opt.plot << "\n";
  }
  print_aa_summary(os, table, aa, aa_references_used(), so.cpu, so.date);
  if (!opt.plot.empty() && write_aa_svg(aa_plot_file(opt.plot), table, aa, so.cpu, so.date))
    os << "Antialiasing plot written to " << aa_plot_file(opt.plot) << "\n";
  std::vector<std::string> names;
  for (const shortcut_set& v : shortcut_sets()) names.push_back(v.name);
  print_shortcuts(os, table, names);
  print_embree_summary(os, table, so.width, so.height);
  print_scale_summary(os, table, opt.quick);
  print_stiff(os, paths(), run_stiff_cases());
  print_sphere_stiff(os, run_sphere_stiff_cases());
  os.flush();
  return 0;
}

}  // namespace
}  // namespace raycast::bench

int main(int argc, char** argv) { return raycast::bench::run(argc, argv); }
