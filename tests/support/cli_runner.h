// Runs the built `raycast` (RAYCAST_EXE) in a fresh temporary directory,
// capturing its exit status, standard output and standard error, and checks
// after every run that no temporary file (".name.XXXXXX") was left behind.
#pragma once
#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#ifndef RAYCAST_EXE
#error "RAYCAST_EXE must name the raycast executable"
#endif

namespace raycast_test {

namespace fs = std::filesystem;

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

inline size_t count_lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Built without the image module (RAYCAST_IMAGE_MODULE=OFF, the aarch64
// cross build), raycast writes PPM only.
inline bool have_image_module() {
  return fs::exists(fs::path(RAYCAST_EXE).parent_path() / "raycast_oiio.so");
}

struct run_result {
  int exit_code = -1;  // when the process exited
  int signal = 0;      // when a signal ended it
  std::string out, err;
};

// One line "raycast: error: ..." on standard error, nothing on standard output.
inline void expect_one_error_line(const run_result& r, const std::string& mentions) {
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << r.err;
  EXPECT_EQ(r.err.rfind("raycast: error: ", 0), 0u) << r.err;
  EXPECT_TRUE(contains(r.err, mentions)) << "want '" << mentions << "' in: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

struct run_options {
  // RLIMIT_FSIZE for the child, with SIGXFSZ ignored: writes past it fail with
  // EFBIG, as on a full disk.
  std::optional<rlim_t> file_size_limit;
  // Standard output goes here instead of the captured file.
  std::optional<std::string> stdout_path;
  // Standard output is this descriptor of the parent (e.g. a pipe's write end;
  // the parent closes its own copy after start()).
  std::optional<int> stdout_fd;
  // Standard output is closed, as after `>&-`.
  bool close_stdout = false;
  // Run as this user and group (from root), e.g. where root would bypass a
  // file permission under test.
  std::optional<std::pair<uid_t, gid_t>> run_as;
  // With file_size_limit: leave SIGXFSZ at its default action (death), as a
  // shell's `ulimit -f` does; raycast must ignore it itself.
  bool default_sigxfsz = false;
  // Other resource limits for the child (soft and hard), e.g. RLIMIT_AS.
  std::vector<std::pair<int, rlim_t>> limits;
  // Signals ignored when raycast starts, as `nohup` leaves SIGHUP.
  std::vector<int> ignored_signals;
  // Extra environment entries, "NAME=value".
  std::vector<std::string> env;
};

// Whether the tests (and the raycast they run) are built with AddressSanitizer
// (GCC's macro, or clang's feature), and whether they run under an emulator:
// a process's limits and peak memory are then not raycast's own.
inline bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#endif
#endif
  return false;
}
inline bool emulated() {
#ifdef RAYCAST_EXE_LAUNCHER
  return true;
#else
  return false;
#endif
}

// The command line that runs the executable `exe`: itself, or in a cross build
// its emulator first (qemu-aarch64 -L ...). RAYCAST_EXE_LAUNCHER is that
// emulator's command line, '|'-separated (tests/CMakeLists.txt).
inline std::vector<std::string> command_for(const std::string& exe) {
  std::vector<std::string> argv;
#ifdef RAYCAST_EXE_LAUNCHER
  const std::string_view launcher = RAYCAST_EXE_LAUNCHER;
  for (size_t b = 0, e; b <= launcher.size(); b = e + 1) {
    e = std::min(launcher.find('|', b), launcher.size());
    argv.emplace_back(launcher.substr(b, e - b));
  }
#endif
  argv.push_back(exe);
  return argv;
}

class cli_sandbox {
 public:
  cli_sandbox() {
    std::string tmpl = (fs::temp_directory_path() / "raycast-test-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp: " + std::string(std::strerror(errno)));
    root_ = tmpl;
    work_ = root_ / "work";
    fs::create_directory(work_);
  }
  ~cli_sandbox() {
    std::error_code ec;
    // Read-only directories made by tests: make them removable again.
    for (auto it = fs::recursive_directory_iterator(root_, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
      if (it->is_directory(ec) && !it->is_symlink(ec)) fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(root_, ec);
  }
  cli_sandbox(const cli_sandbox&) = delete;
  cli_sandbox& operator=(const cli_sandbox&) = delete;

  // Lets other users reach work() and run raycast (for run_options::run_as).
  // The build tree may sit where they cannot go (a clone under a 0700 /root,
  // as on a fresh machine), so they run a copy of the executable and of the
  // image module it loads from beside itself.
  void open_to_others() {
    const fs::perms open = fs::perms::all & ~fs::perms::others_write & ~fs::perms::group_write;
    fs::permissions(root_, open);
    fs::permissions(work_, open);
    const fs::path exe = RAYCAST_EXE, bin = root_ / "bin";
    fs::create_directory(bin);
    fs::permissions(bin, open);
    for (const fs::path& name : {exe.filename(), fs::path("raycast_oiio.so")}) {
      if (!fs::exists(exe.parent_path() / name)) continue;  // a build without the image module
      fs::copy_file(exe.parent_path() / name, bin / name, fs::copy_options::overwrite_existing);
      fs::permissions(bin / name, open);
    }
    shared_exe_ = (bin / exe.filename()).string();
  }

  // The directory the CLI runs in and writes to; empty at the start.
  const fs::path& work() const { return work_; }
  std::string path(const std::string& name) const { return (work_ / name).string(); }

  // Every name under work(), relative, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(work_, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
      names.push_back(it->path().lexically_relative(work_).string());  // no link followed
    std::sort(names.begin(), names.end());
    return names;
  }

  // Names under work() starting with '.': temporary files left behind.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> dot;
    for (const std::string& n : entries())
      if (fs::path(n).filename().string().rfind('.', 0) == 0) dot.push_back(n);
    return dot;
  }

  // The size of the file a running raycast is writing under work(): an
  // unnamed O_TMPFILE file, seen through /proc/<pid>/fd, or a named temporary
  // where the file system has no O_TMPFILE. nullopt until there is one.
  std::optional<uintmax_t> output_in_progress(pid_t pid) const {
    std::error_code ec;
    const fs::path fds = fs::path("/proc") / std::to_string(pid) / "fd";
    for (auto it = fs::directory_iterator(fds, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
      const fs::path target = fs::read_symlink(it->path(), ec);
      if (ec) {
        ec.clear();
        continue;
      }
      if (target.parent_path() != work_ && target.string().rfind(work_.string() + "/", 0) != 0) continue;
      struct stat st {};
      if (stat(it->path().c_str(), &st) == 0 && S_ISREG(st.st_mode)) return uintmax_t(st.st_size);
    }
    const auto dot = leftovers();
    if (dot.empty()) return std::nullopt;
    const uintmax_t n = fs::file_size(work_ / dot.front(), ec);
    return ec ? std::optional<uintmax_t>() : n;
  }

  pid_t start(const std::vector<std::string>& args, const run_options& opts = {}) const {
    const std::string exe = opts.run_as && !shared_exe_.empty() ? shared_exe_ : RAYCAST_EXE;
    std::vector<std::string> argv_s = command_for(exe);
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_s = opts.env;
    // Ours replace the inherited entries of the same names (an emulator's
    // environment keeps the last of two, glibc's getenv the first).
    for (char** e = environ; *e; ++e) {
      const std::string_view entry(*e);
      const std::string_view name = entry.substr(0, entry.find('=') + 1);
      if (std::none_of(opts.env.begin(), opts.env.end(), [&](const std::string& o) { return o.rfind(name, 0) == 0; }))
        env_s.emplace_back(*e);
    }
    std::vector<char*> envp;
    for (std::string& e : env_s) envp.push_back(e.data());
    envp.push_back(nullptr);
    const std::string out = opts.stdout_path.value_or(out_path()), err = err_path(),
                      cwd = work_.string();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
    if (pid == 0) {
      // Only async-signal-safe calls between fork and exec.
      // O_CLOEXEC: only the dup2'ed copies 0, 1, 2 reach raycast.
      const int in_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
      const int out_fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      const int err_fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (in_fd < 0 || out_fd < 0 || err_fd < 0) _exit(125);
      if (dup2(in_fd, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0) _exit(125);
      if (opts.stdout_fd && dup2(*opts.stdout_fd, 1) < 0) _exit(125);
      for (int fd = 0; fd <= 2; ++fd) fcntl(fd, F_SETFD, 0);  // dup2 onto itself keeps O_CLOEXEC
      if (opts.close_stdout) close(1);
      if (chdir(cwd.c_str()) != 0) _exit(125);
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      struct sigaction ignore {};
      ignore.sa_handler = SIG_IGN;
      if (opts.file_size_limit) {
        if (!opts.default_sigxfsz) sigaction(SIGXFSZ, &ignore, nullptr);
        const struct rlimit rl = {*opts.file_size_limit, *opts.file_size_limit};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(125);
      }
      for (const int sig : opts.ignored_signals) sigaction(sig, &ignore, nullptr);
      if (opts.run_as) {
        if (setgroups(0, nullptr) != 0 || setgid(opts.run_as->second) != 0 ||
            setuid(opts.run_as->first) != 0)
          _exit(125);
      }
      // After setuid: RLIMIT_NPROC counts the processes of the user we run as.
      for (const auto& [resource, value] : opts.limits) {
        const struct rlimit rl = {value, value};
        if (setrlimit(resource, &rl) != 0) _exit(125);
      }
      execve(argv[0], argv.data(), envp.data());
      _exit(127);
    }
    return pid;
  }

  // Waits for the process; checks that it left no temporary file.
  run_result finish(pid_t pid) const {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
      if (errno != EINTR) throw std::runtime_error("waitpid: " + std::string(std::strerror(errno)));
    run_result r;
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    r.out = read_file(out_path());
    r.err = read_file(err_path());
    EXPECT_NE(r.exit_code, 125) << "could not set up the child process";
    EXPECT_NE(r.exit_code, 127) << "could not execute " << RAYCAST_EXE;
    const auto dot = leftovers();
    EXPECT_TRUE(dot.empty()) << "temporary file left behind: " << dot.front();
    return r;
  }

  run_result run(const std::vector<std::string>& args, const run_options& opts = {}) const {
    return finish(start(args, opts));
  }

 private:
  std::string out_path() const { return (root_ / "stdout").string(); }
  std::string err_path() const { return (root_ / "stderr").string(); }

  fs::path root_, work_;
  std::string shared_exe_;  // set by open_to_others()
};

// A binary PPM (P6) parsed strictly: magic, width, height, maxval, one
// whitespace byte, then exactly width * height * 3 bytes.
struct ppm {
  int64_t width = 0, height = 0, maxval = 0;
  std::string header, pixels;
  std::string error;  // empty when it parsed
};

inline ppm parse_ppm(const std::string& data) {
  ppm p;
  size_t pos = 0;
  auto skip_space = [&] {
    while (pos < data.size()) {
      if (data[pos] == '#') {
        while (pos < data.size() && data[pos] != '\n') ++pos;
      } else if (std::isspace(static_cast<unsigned char>(data[pos]))) {
        ++pos;
      } else {
        break;
      }
    }
  };
  auto number = [&](int64_t& v) {
    skip_space();
    const size_t begin = pos;
    v = 0;
    while (pos < data.size() && data[pos] >= '0' && data[pos] <= '9' && v < (int64_t{1} << 40))
      v = v * 10 + (data[pos++] - '0');
    return pos > begin;
  };
  if (data.compare(0, 2, "P6") != 0) {
    p.error = "no P6 magic";
    return p;
  }
  pos = 2;
  if (!number(p.width) || !number(p.height) || !number(p.maxval)) {
    p.error = "bad header numbers";
    return p;
  }
  if (pos >= data.size() || !std::isspace(static_cast<unsigned char>(data[pos]))) {
    p.error = "no whitespace after maxval";
    return p;
  }
  ++pos;
  p.header = data.substr(0, pos);
  p.pixels = data.substr(pos);
  if (p.maxval != 255) p.error = "maxval is not 255";
  else if (p.pixels.size() != size_t(p.width) * size_t(p.height) * 3)
    p.error = "pixel data is " + std::to_string(p.pixels.size()) + " bytes, want " +
              std::to_string(p.width * p.height * 3);
  return p;
}

// What a fault test writes first, to check that a failure leaves it intact.
inline const std::string precious = "precious: the user's last good image\n";

inline std::string how_it_ended(const run_result& r) {
  if (r.signal != 0) return std::string("killed by signal ") + strsignal(r.signal);
  return "exit status " + std::to_string(r.exit_code);
}

// The one shape of a runtime failure: exit 1, one line naming the file and the
// cause, nothing on standard output.
inline void expect_runtime_error(const run_result& r, const std::string& file, const std::string& cause) {
  EXPECT_EQ(r.signal, 0) << how_it_ended(r) << "; standard error: " << r.err;
  EXPECT_EQ(r.exit_code, 1) << how_it_ended(r) << "; standard error: " << r.err;
  EXPECT_EQ(r.err, "raycast: error: " + file + ": " + cause + "\n");
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out.size() << " bytes on standard output";
}

// A usage error: exit 2 and exactly this one line.
inline void expect_usage_error(const run_result& r, const std::string& line) {
  EXPECT_EQ(r.signal, 0) << how_it_ended(r);
  EXPECT_EQ(r.exit_code, 2) << how_it_ended(r) << "; standard error: " << r.err;
  EXPECT_EQ(r.err, "raycast: error: " + line + "\n");
}

// Exit 0 and nothing on standard error.
inline void expect_success(const run_result& r) {
  EXPECT_EQ(r.signal, 0) << how_it_ended(r) << "; standard error: " << r.err;
  EXPECT_EQ(r.exit_code, 0) << how_it_ended(r) << "; standard error: " << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace raycast_test
