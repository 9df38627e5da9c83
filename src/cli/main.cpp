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
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/files/signals.h"
#include "io/timestamp.h"
#include "options.h"
#include "raycast/raycast.h"
#include "text/names.h"
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

// What --stats reports: each stage's seconds, which add up to the run's.
struct run_stats {
  double prepare = 0;  // the job: the float scene, culling, the light's structures
  api::job::timings output;
  api::job::stats job;
  uint64_t rays = 0;  // pixels x samples
};

int run(cli::job& j, run_stats& st) {
  auto t = clock::now();
  const api::job job(std::move(j.description), j.options);  // moves the spheres; freed once prepared
  st.prepare = seconds_since(t);
  st.job = job.statistics();
  const int64_t W = job.width(), H = job.height();
  progress bar(!j.quiet && isatty(STDERR_FILENO), H);
  st.output = job.write(j.output, j.options.format, [&bar](int64_t rows_done, const char* phase) { bar.show(rows_done, phase); });
  st.rays = uint64_t(W) * uint64_t(H) * st.job.samples;
  return 0;
}

// --stats: a short block with stable labels (tests read it), like pbrt's.
// Every stage of the run is a line, so that they add up to the total but
// for the parsing of the options and the process's start and end.
void print_stats(const cli::job& j, const run_stats& st, double total) {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double rays_per_second = st.output.render > 0 ? double(st.rays) / st.output.render : 0.0;
  std::fprintf(stderr, "raycast stats:\n  load      %10.4f s\n  prepare   %10.4f s\n", j.load_seconds, st.prepare);
  // Where shadow or AO rays are cast: what their structures took of prepare.
  if (st.job.light_bytes > 0)
    std::fprintf(stderr, "  light     %10.4f s  (of prepare: %.1f MB for shadow and AO rays)\n", st.job.light_seconds,
                 double(st.job.light_bytes) / 1e6);
  std::fprintf(stderr,
               "  open      %10.4f s  (the output file, and the image library where its format needs it)\n"
               "  render    %10.4f s\n"
               "  write     %10.4f s\n"
               "  total     %10.4f s\n"
               "  rays/s    %10.4g  (%llu rays)\n"
               "  spheres   %10zu\n"
               "  peak RSS  %10.1f MB\n",
               st.output.open, st.output.render, st.output.write, total, rays_per_second,
               static_cast<unsigned long long>(st.rays), st.job.spheres, double(ru.ru_maxrss) * 1024.0 / 1e6);
}

void print_error(std::string_view what) {
  std::cerr << "raycast: error: " << cli::printable(what) << "\n";
}

// --help and --version print to standard output: a failed write there (closed,
// full, a reader gone) is a failure too, reported like any other. The text
// goes out in one write, so that the error is that write's.
bool written_to_standard_output(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0 &&
      !std::ferror(stdout))
    return true;
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
  if (auto isa = unknown_max_isa()) {
    print_error("RAYCAST_MAX_ISA: " + not_one_of(*isa, "'" + *isa + "'", target_names()));
    return 2;
  }
  std::ostringstream out;
  cli::parse_result parsed = cli::parse_args(argc, argv, out, std::cerr);
  if (!parsed.run) {
    if (parsed.exit_code == 0 && !written_to_standard_output(out.str())) return 1;
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
  } catch (const api::error& e) {
    // The job's own checks (a backend this CPU cannot run, --precision fast
    // with spheres) are usage errors, named by their option; writing fails
    // with the file's name.
    if (e.kind() == api::error::kind::io) {
      print_error(e.message());
      return 1;
    }
    print_error("--" + e.field() + ": " + e.message());
    return 2;
  } catch (const std::bad_alloc&) {
    print_error(parsed.run->output + ": out of memory");
  } catch (const std::exception& e) {
    // Anything else still unwinds, so the temporary file is removed.
    print_error(parsed.run->output + ": " + e.what());
  }
  return 1;
}
