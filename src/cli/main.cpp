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
#include "io/io_error.h"
#include "io/timestamp.h"
#include "options.h"
#include "run.h"
#include "raycast/raycast.h"
#include "text/names.h"
#include "simd/cpu.h"

namespace {

using namespace raycast;

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

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
    cli::run_stats st;
    cli::run(*parsed.run, st);
    if (parsed.run->stats) cli::print_stats(st, seconds_since(start));
    return 0;
  } catch (const refusal& r) {  // a frame the file cannot give
    int code = 2;
    print_error(cli::refusal_text(r, code));
    return code;
  } catch (const io::io_error& e) {
    print_error(e.what());
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
