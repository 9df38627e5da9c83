#include "trajectory_rows.h"

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "formats_rows.h"
#include "rows.h"

extern char** environ;

namespace raycast::bench {
namespace {

// What one raycast run said: its --stats lines (name -> seconds, or MB for
// peak RSS), or the reason it has none.
struct run_result {
  std::map<std::string, double> stats;
  std::string error;
};

// "  load      0.0013 s" -> stats["load"]; "  peak RSS  132.2 MB" -> stats["peak RSS"].
void parse_stats(const std::string& text, run_result& r) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 12 || line.compare(0, 2, "  ") != 0) continue;
    const std::string name = line.substr(2, 10);
    const size_t end = name.find_last_not_of(' ');
    if (end == std::string::npos) continue;
    char* after = nullptr;
    const double v = std::strtod(line.c_str() + 12, &after);
    if (after != line.c_str() + 12) r.stats[name.substr(0, end + 1)] = v;
  }
}

// Runs the program with args, its standard error read back; stdout to /dev/null.
run_result run_program(const std::vector<std::string>& args) {
  run_result r;
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return r.error = "pipe failed", r;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, pipe_fds[1], 2);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  close(pipe_fds[1]);
  std::string text;
  char buf[4096];
  for (ssize_t n; spawned == 0 && (n = read(pipe_fds[0], buf, sizeof buf)) > 0;) text.append(buf, size_t(n));
  close(pipe_fds[0]);
  if (spawned != 0) return r.error = "cannot run " + args[0], r;
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return r.error = text.substr(0, text.find('\n')), r;
  parse_stats(text, r);
  if (!r.stats.count("total") || !r.stats.count("peak RSS")) r.error = "no --stats from " + args[0];
  return r;
}

// The counters of one run, with `prefix` ("" or "one_").
void put(benchmark::State& state, const run_result& r, const std::string& prefix) {
  for (const char* k : {"load", "prepare", "render", "open", "write"})
    state.counters[prefix + k] = r.stats.count(k) ? r.stats.at(k) : 0.0;
  state.counters[prefix + "seconds"] = r.stats.at("total");
  state.counters[prefix + "peak_rss_mb"] = r.stats.at("peak RSS");
}

void bench_frames(benchmark::State& state, int64_t atoms, int frames, int64_t w, int64_t h) {
  const std::string dump = dump_file(frames, atoms);
  if (dump.empty()) return state.SkipWithError("cannot write the dump in $TMPDIR/raycast-bench-formats");
  const std::string program = exe_dir() + "/raycast";
  if (access(program.c_str(), X_OK) != 0) return state.SkipWithError(("no " + program).c_str());
  char dir_template[] = "/tmp/raycast-bench-frames-XXXXXX";
  if (!mkdtemp(dir_template)) return state.SkipWithError("cannot make a directory in /tmp");
  const std::string dir = dir_template;
  const std::vector<std::string> common = {program, "--scene", dump, "--threads", "1", "--stats", "-q",
                                           "--width", std::to_string(w), "--height", std::to_string(h)};
  run_result many, one;
  for (auto _ : state) {
    std::vector<std::string> a = common, b = common;
    a.insert(a.end(), {"-o", dir + "/f_%04d.png"});
    b.insert(b.end(), {"-o", dir + "/one.png", "--frames", "0"});
    many = run_program(a);
    one = run_program(b);
    if (!many.error.empty() || !one.error.empty()) break;
  }
  std::filesystem::remove_all(dir);
  if (!many.error.empty() || !one.error.empty())
    return state.SkipWithError((many.error.empty() ? one.error : many.error).c_str());
  put(state, many, "");
  put(state, one, "one_");
}

}  // namespace

void register_trajectory_rows(bool quick) {
  struct shape {
    int64_t atoms;
    int frames;
    int64_t w, h;
  };
  const std::vector<shape> shapes = quick ? std::vector<shape>{{10000, 12, 480, 270}, {2000, 100, 480, 270}}
                                          : std::vector<shape>{{100000, 12, 1920, 1080}, {2000, 1000, 640, 360}};
  for (const shape& s : shapes) {
    const std::string sz = size_text(s.w, s.h);
    add_row("frames/" + std::to_string(s.atoms) + "/" + std::to_string(s.frames) + "/" + sz,
            strf("kind=frames atoms=%lld frames=%d size=%s threads=1 out=png", static_cast<long long>(s.atoms),
                 s.frames, sz.c_str()),
            benchmark::kSecond, bench_frames, s.atoms, s.frames, s.w, s.h)
        ->Iterations(1)
        ->Repetitions(quick ? 1 : 3)
        ->ReportAggregatesOnly(false);
  }
}

}  // namespace raycast::bench
