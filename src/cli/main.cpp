// raycast: parse, render in bands of rows, hand each band to the sink.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/image_sink.h"
#include "io/signals.h"
#include "io/timestamp.h"
#include "options.h"
#include "raycast/bands.h"
#include "render/render.h"
#include "simd/cpu.h"

namespace {

using namespace raycast;

// The lesson's "Scanlines remaining" with a bar and the phase (rendering or
// writing a band), shown only to a person at a terminal.
class progress {
 public:
  progress(bool enabled, int64_t rows) : on_(enabled), rows_(rows) {}
  void show(int64_t rows_done, const char* phase) {
    if (!on_) return;
    constexpr int width = 30;
    const int filled = int(width * rows_done / rows_);
    std::fprintf(stderr, "\rScanlines remaining: %lld [%.*s%*s] %3d%% %-9s",
                 static_cast<long long>(rows_ - rows_done), filled,
                 "##############################", width - filled, "",
                 int(100 * rows_done / rows_), phase);
    std::fflush(stderr);
  }
  ~progress() {
    if (on_) std::fputs("\r\033[K", stderr);  // leave a clean line behind
  }

 private:
  bool on_;
  int64_t rows_;
};

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

// What --stats reports, besides the job's load time.
struct run_stats {
  double prepare = 0, render = 0, write = 0;  // seconds
  double light = 0;                           // of prepare: shadow and AO structures (0: none)
  size_t light_bytes = 0;
  size_t light_lists = 0, cache_bytes = 0;    // of render: near-field lists gathered, and their caches
  double list_seconds = 0;                    // ... and the threads' seconds gathering them
  uint64_t rays = 0;                          // pixels x samples
  size_t spheres = 0;
};

int run(cli::job& j, run_stats& st) {
  auto t = clock::now();
  const renderer r(j.sc, j.render);
  st.prepare = seconds_since(t);
  st.light = r.light_seconds();
  st.light_bytes = r.light_bytes();
  // The renderer keeps its own copy of the scene: the job's spheres (a scene
  // file's millions) are not needed any more.
  st.spheres = j.sc.arrays ? j.sc.arrays->count : j.sc.spheres.size();
  std::vector<sphere>().swap(j.sc.spheres);
  // The output is the region (the whole image unless --region), rendered
  // and written in bands of whole region rows (raycast/bands.h).
  const cli::pixel_region& reg = j.region;
  const int64_t W = reg.width(), H = reg.height();
  auto sink = io::open_sink(j.output, j.format, W, H);
  progress bar(!j.quiet && isatty(STDERR_FILENO), H);
  const band_timings bt =
      render_to_sink(r, pixel_rect{reg.x0, reg.y0, reg.x1, reg.y1}, io::pixel_format_for(j.format), *sink, j.output,
                     [&bar](int64_t rows_done, const char* phase) { bar.show(rows_done, phase); });
  st.render = bt.render;
  st.write = bt.write;
  st.light_lists = r.light_lists();
  st.list_seconds = r.light_list_seconds();
  st.cache_bytes = r.light_bytes() - st.light_bytes;
  st.rays = uint64_t(W) * uint64_t(H) * r.samples();
  return 0;
}

// --stats: a short block with stable labels (tests read it), like pbrt's.
void print_stats(const cli::job& j, const run_stats& st, double total) {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double rays_per_second = st.render > 0 ? double(st.rays) / st.render : 0.0;
  std::fprintf(stderr, "raycast stats:\n  load      %10.4f s\n  prepare   %10.4f s\n", j.load_seconds, st.prepare);
  // Where shadow or AO rays are cast: what their structures took of prepare.
  if (st.light_bytes > 0)
    std::fprintf(stderr, "  light     %10.4f s  (of prepare: %.1f MB for shadow and AO rays)\n", st.light,
                 double(st.light_bytes) / 1e6);
  std::fprintf(stderr, "  render    %10.4f s\n", st.render);
  if (st.light_bytes > 0)
    std::fprintf(stderr, "  lists     %10zu    (of render: the seen spheres' near-field lists, %.4f s, %.1f MB of caches)\n",
                 st.light_lists, st.list_seconds, double(st.cache_bytes) / 1e6);
  std::fprintf(stderr,
               "  write     %10.4f s\n"
               "  total     %10.4f s\n"
               "  rays/s    %10.4g  (%llu rays)\n"
               "  spheres   %10zu\n"
               "  peak RSS  %10.1f MB\n",
               st.write, total, rays_per_second, static_cast<unsigned long long>(st.rays), st.spheres,
               double(ru.ru_maxrss) * 1024.0 / 1e6);
}


void print_error(std::string_view what) {
  std::cerr << "raycast: error: " << cli::printable(what) << "\n";
}

// --help and --version print to standard output: a failed write there (closed,
// full, a reader gone) is a failure too, reported like any other.
bool standard_output_flushed() {
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return true;
  const int e = errno;
  print_error(std::string("standard output: ") + (e != 0 ? std::strerror(e) : "write error"));
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const auto start = clock::now();
  io::reserve_standard_streams();
  io::install_signal_handlers();
  // The environment is part of the command: a malformed value is refused
  // like a malformed option, before anything is touched -- RAYCAST_MAX_ISA
  // before anything is printed (--version names the backend it caps).
  if (auto why = max_isa_error()) {
    print_error("RAYCAST_MAX_ISA: " + *why);
    return 2;
  }
  cli::parse_result parsed = cli::parse_args(argc, argv, std::cout, std::cerr);
  if (!parsed.run) {
    if (parsed.exit_code == 0 && !standard_output_flushed()) return 1;
    return parsed.exit_code;
  }
  if (auto why = io::source_date_epoch().error) {
    print_error("SOURCE_DATE_EPOCH: " + *why);
    return 2;
  }
  try {
    run_stats st;
    const int code = run(*parsed.run, st);
    if (parsed.run->stats) print_stats(*parsed.run, st, seconds_since(start));
    return code;
  } catch (const io::io_error& e) {
    print_error(e.what());
  } catch (const unsupported_backend& e) {
    print_error(std::string("--backend: ") + e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    print_error(parsed.run->output + ": out of memory");
  } catch (const std::exception& e) {
    // Anything else still unwinds, so the temporary file is removed.
    print_error(parsed.run->output + ": " + e.what());
  }
  return 1;
}
