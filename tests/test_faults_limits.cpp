// The fault matrix, continued: resource limits, odd destinations,
// format limits. Same promises as test_faults.cpp — a runtime failure is exit
// 1 with one "raycast: error: <file>: <cause>" line, no temporary file left
// (cli_sandbox::finish checks), the old file as it was; a usage error is exit
// 2 and touches nothing — under a container's limits, `nohup`, shared
// directories and the encoders' own limits.
//
// Cases that need root (another user, RLIMIT_NPROC, mounts) run a forked
// child as `nobody` and skip, with the reason, where they cannot.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::count_lines;
using raycast_test::emulated;
using raycast_test::expect_runtime_error;
using raycast_test::sanitized;
using raycast_test::how_it_ended;
using raycast_test::precious;
using raycast_test::have_image_module;
using raycast_test::parse_ppm;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;
using raycast_test::write_file;

namespace fs = std::filesystem;

constexpr uid_t nobody = 65534;
constexpr gid_t nogroup = 65534;


using raycast_test::expect_success;
using raycast_test::expect_usage_error;

// A 400x225 PPM as raycast writes it by default.
void expect_default_ppm(const fs::path& p) {
  const auto ppm = parse_ppm(read_file(p));
  EXPECT_EQ(ppm.error, "") << p;
  EXPECT_EQ(ppm.width, 400);
  EXPECT_EQ(ppm.height, 225);
}

// Root, and a `nobody` that can reach the sandbox; otherwise the reason.
std::string cannot_run_as_nobody(cli_sandbox& box) {
  if (geteuid() != 0) return "needs root to run a child as nobody; this is uid " + std::to_string(geteuid());
  box.open_to_others();
  return "";
}

// ---------------------------------------------------------------- threads

// OMP_STACKSIZE that no address space holds: libgomp could not start a
// thread and called exit() with its own line. raycast renders on the threads
// that do start (here: one) and succeeds; OpenImageIO's threads use the
// default stack and start.
class ThreadsCannotStart : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(ThreadsCannotStart, HugeOmpStackSizeFallsBackToFewerThreads) {
  run_options opts;
  opts.env = {"OMP_STACKSIZE=100G"};
  const std::string name = std::string("sky.") + GetParam();
  // 2000 x 1125: large enough that the render asks for every core.
  const run_result r = box.run({"-w", "2000", "-q", "-o", name}, opts);
  expect_success(r);
  EXPECT_GT(fs::file_size(box.work() / name), 1000u);
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});
}

// A pids limit (RLIMIT_NPROC = 1 for the user): no thread at all can start.
// A PPM renders on the calling thread; the image module's libraries start
// threads in their static constructors (log4cplus, through OpenImageIO's
// dependencies) and cannot be loaded: one line, exit 1, nothing created.
TEST_P(ThreadsCannotStart, PidsLimitGivesOneThreadOrOneLine) {
  if (sanitized()) GTEST_SKIP() << "LeakSanitizer starts a thread at exit, which this limit forbids";
  if (emulated()) GTEST_SKIP() << "the limit would bind the emulator's threads";
  if (const std::string why = cannot_run_as_nobody(box); !why.empty()) GTEST_SKIP() << why;
  fs::permissions(box.work(), fs::perms::all);  // nobody writes the image here
  run_options opts;
  opts.run_as = std::pair<uid_t, gid_t>{nobody, nogroup};
  opts.limits = {{RLIMIT_NPROC, 1}};
  const std::string name = std::string("sky.") + GetParam();
  const run_result r = box.run({"-w", "2000", "-q", "-o", name}, opts);
  if (std::string(GetParam()) == "ppm") {
    expect_success(r);
    EXPECT_EQ(box.entries(), std::vector<std::string>{name});
  } else {
    EXPECT_EQ(r.exit_code, 1) << how_it_ended(r) << ": " << r.err;
    EXPECT_EQ(r.err.rfind("raycast: error: " + name + ": ", 0), 0u) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_TRUE(box.entries().empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, ThreadsCannotStart, ::testing::Values("ppm", "png", "exr"),
                         [](const auto& p) { return std::string(p.param); });

// ---------------------------------------------------------------- address space

// Whether pid ended within `limit` (it stays a zombie for finish()).
bool ends_within(pid_t pid, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  for (;;) {
    siginfo_t info {};
    if (waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// ulimit -v from well below to above what loading OpenImageIO's ~260
// libraries takes. Depending on where the limit bites, their static
// constructors fail to map, throw bad_alloc, call std::terminate, dereference
// a failed allocation, or deadlock with every signal blocked (log4cplus's
// thread pool). Every run must end with success, or with one line and exit 1,
// and leave no file; a run still going after 10 s must die of SIGTERM at once
// (raycast keeps a thread that takes signals while the module loads, and
// gives up on the load after 30 s).
TEST(AddressSpaceLimit, EveryLimitSucceedsOrFailsWithOneLine) {
  if (sanitized()) GTEST_SKIP() << "the sanitizers reserve terabytes of address space";
  if (emulated()) GTEST_SKIP() << "the limit would bind the emulator";
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  cli_sandbox box;
  int succeeded = 0, failed = 0;
  for (rlim_t mib = 100; mib <= 700; mib += 20) {
    SCOPED_TRACE("ulimit -v " + std::to_string(mib * 1024));
    run_options opts;
    opts.limits = {{RLIMIT_AS, mib << 20}};
    const pid_t pid = box.start({"-q", "-o", "sky.png"}, opts);
    if (!ends_within(pid, std::chrono::seconds(10))) {
      kill(pid, SIGTERM);
      const bool killable = ends_within(pid, std::chrono::seconds(5));
      if (!killable) kill(pid, SIGKILL);
      const run_result r = box.finish(pid);
      EXPECT_TRUE(killable) << "SIGTERM did not end it within 5 s";
      EXPECT_EQ(r.signal, SIGTERM) << how_it_ended(r) << ": " << r.err;
      EXPECT_TRUE(box.entries().empty());
      continue;
    }
    const run_result r = box.finish(pid);
    EXPECT_EQ(r.signal, 0) << how_it_ended(r) << ": " << r.err;
    if (r.exit_code == 0) {
      ++succeeded;
      EXPECT_TRUE(r.err.empty()) << r.err;
      EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.png"});
      fs::remove(box.work() / "sky.png");
    } else {
      ++failed;
      EXPECT_EQ(r.exit_code, 1) << r.err;
      EXPECT_EQ(r.err.rfind("raycast: error: sky.png: ", 0), 0u) << r.err;
      EXPECT_EQ(count_lines(r.err), 1u) << r.err;
      EXPECT_TRUE(box.entries().empty());
    }
  }
  EXPECT_GT(failed, 0) << "no limit was tight enough to fail: the sweep tests nothing";
  EXPECT_GT(succeeded, 0) << "no limit was loose enough to succeed";
}

// The first loader error names the cause (a library that cannot be mapped),
// not that the second place looked in has no module.
TEST(AddressSpaceLimit, ReportsTheFirstLoaderError) {
  if (sanitized()) GTEST_SKIP() << "the sanitizers reserve terabytes of address space";
  if (emulated()) GTEST_SKIP() << "the limit would bind the emulator";
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  cli_sandbox box;
  run_options opts;
  opts.limits = {{RLIMIT_AS, rlim_t{150} << 20}};
  const run_result r = box.run({"-q", "-o", "sky.png"}, opts);
  EXPECT_EQ(r.exit_code, 1) << how_it_ended(r) << ": " << r.err;
  EXPECT_EQ(r.err.rfind("raycast: error: sky.png: cannot load the image module (", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("raycast_oiio.so: cannot open shared object file"), std::string::npos) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

// ---------------------------------------------------------------- file size limit

// `ulimit -f` as a shell sets it: SIGXFSZ at its default (death). raycast
// ignores it, so the write fails with EFBIG like a full disk.
class FileSizeLimit : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(FileSizeLimit, IsFileTooLargeAndKeepsTheOldFile) {
  const std::string name = std::string("big.") + GetParam();
  write_file(box.work() / name, precious);
  run_options opts;
  opts.file_size_limit = 64 * 1024;
  opts.default_sigxfsz = true;
  const run_result r = box.run({"-w", "1920", "-o", name}, opts);
  expect_runtime_error(r, name, "File too large");
  EXPECT_EQ(read_file(box.work() / name), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});
}

INSTANTIATE_TEST_SUITE_P(Formats, FileSizeLimit, ::testing::Values("png", "ppm", "jpg", "tif", "exr"),
                         [](const auto& p) { return std::string(p.param); });

// ---------------------------------------------------------------- signals

// Sent while writing a long job: the process dies of the same signal,
// nothing is left, the old file stays. (SIGINT, SIGTERM, SIGHUP:
// test_faults.cpp.) Core dumps are off, so SIGQUIT leaves no core file.
class FatalSignal : public ::testing::TestWithParam<int> {
 protected:
  cli_sandbox box;
};

run_result stop_while_writing(const cli_sandbox& box, const std::string& name, int sig,
                              uintmax_t after_bytes, const run_options& opts, bool& reached) {
  const pid_t pid = box.start({"--width", "16384", "--height", "9216", "-q", "-o", name}, opts);
  reached = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!reached && std::chrono::steady_clock::now() < deadline) {
    const auto size = box.output_in_progress(pid);
    reached = size && *size >= after_bytes;
    if (!reached) {
      siginfo_t info {};
      if (waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid) break;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  kill(pid, reached ? sig : SIGKILL);
  return box.finish(pid);
}

TEST_P(FatalSignal, CleansUpLikeSigterm) {
  const int sig = GetParam();
  write_file(box.work() / "big.ppm", precious);
  run_options opts;
  opts.limits = {{RLIMIT_CORE, 0}};
  bool reached = false;
  const run_result r = stop_while_writing(box, "big.ppm", sig, 1 << 20, opts, reached);
  ASSERT_TRUE(reached) << "the output never reached 1 MiB: " << how_it_ended(r) << " " << r.err;
  EXPECT_EQ(r.signal, sig) << how_it_ended(r) << ": " << r.err;
  EXPECT_EQ(read_file(box.work() / "big.ppm"), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"big.ppm"});
}

INSTANTIATE_TEST_SUITE_P(Signals, FatalSignal,
                         ::testing::Values(SIGQUIT, SIGXCPU, SIGUSR1, SIGALRM, SIGVTALRM),
                         [](const auto& p) { return std::string(sigabbrev_np(p.param)); });

// SIGKILL cannot be handled: the output has no name until it is complete
// (O_TMPFILE), so there is nothing to leave behind.
TEST(Sigkill, MidWriteLeavesNothingVisible) {
  cli_sandbox box;
  const int probe = open(box.work().c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (probe < 0)
    GTEST_SKIP() << "the file system under " << box.work() << " has no O_TMPFILE ("
                 << std::strerror(errno) << "): raycast falls back to a named temporary there";
  close(probe);
  if (access("/proc/self/fd", X_OK) != 0) GTEST_SKIP() << "no /proc here: raycast uses a named temporary";
  write_file(box.work() / "big.ppm", precious);
  bool reached = false;
  const run_result r = stop_while_writing(box, "big.ppm", SIGKILL, 1 << 20, {}, reached);
  ASSERT_TRUE(reached) << "the output never reached 1 MiB: " << how_it_ended(r) << " " << r.err;
  EXPECT_EQ(r.signal, SIGKILL);
  EXPECT_EQ(read_file(box.work() / "big.ppm"), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"big.ppm"});  // finish() checked for temporaries too
}

// `nohup raycast ...`: SIGHUP ignored at start stays ignored; the render
// completes.
TEST(Nohup, IgnoredSighupStaysIgnored) {
  cli_sandbox box;
  run_options opts;
  opts.ignored_signals = {SIGHUP};
  const pid_t pid = box.start({"--width", "4096", "-q", "-o", "sky.ppm"}, opts);
  for (int i = 0; i < 200 && !box.output_in_progress(pid); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGHUP);
  const run_result r = box.finish(pid);
  expect_success(r);
  const auto ppm = parse_ppm(read_file(box.work() / "sky.ppm"));
  EXPECT_EQ(ppm.error, "");
  EXPECT_EQ(ppm.width, 4096);
}

// ---------------------------------------------------------------- whose file it is

// A file its owner made read-only is refused, as `cp` and `>` refuse it:
// renaming over it would only need the directory's permission.
TEST(ReadOnlyDestination, RefusedForItsOwner) {
  cli_sandbox box;
  run_options opts;
  if (geteuid() == 0) {
    box.open_to_others();
    fs::permissions(box.work(), fs::perms::all);  // nobody may create files here
    opts.run_as = std::pair<uid_t, gid_t>{nobody, nogroup};
  }
  write_file(box.work() / "sky.ppm", precious);
  ASSERT_EQ(chown((box.work() / "sky.ppm").c_str(), geteuid() == 0 ? nobody : geteuid(), getegid()), 0);
  ASSERT_EQ(chmod((box.work() / "sky.ppm").c_str(), 0444), 0);
  const run_result r = box.run({"-o", "sky.ppm"}, opts);
  expect_runtime_error(r, "sky.ppm", "Permission denied");
  EXPECT_EQ(read_file(box.work() / "sky.ppm"), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.ppm"});
}

// root replacing another user's file keeps its owner, group and mode, as
// writing into it would.
TEST(ReplacedFile, KeepsOwnerGroupAndMode) {
  cli_sandbox box;
  if (geteuid() != 0) GTEST_SKIP() << "giving a file to another user needs root";
  const fs::path dest = box.work() / "sky.ppm";
  write_file(dest, precious);
  ASSERT_EQ(chown(dest.c_str(), nobody, nogroup), 0);
  ASSERT_EQ(chmod(dest.c_str(), 0640), 0);
  expect_success(box.run({"-o", "sky.ppm"}));
  struct stat st {};
  ASSERT_EQ(stat(dest.c_str(), &st), 0);
  EXPECT_EQ(st.st_uid, nobody);
  EXPECT_EQ(st.st_gid, nogroup);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  expect_default_ppm(dest);
}

// Decided: the name is replaced, not the file. Another hard link keeps the
// old image; writing into the shared file instead would damage it when a
// write fails half-way, which is the promise this writer exists for.
TEST(ReplacedFile, AnotherHardLinkKeepsTheOldImage) {
  cli_sandbox box;
  const fs::path dest = box.work() / "sky.ppm", other = box.work() / "other.ppm";
  write_file(dest, precious);
  fs::create_hard_link(dest, other);
  expect_success(box.run({"-o", "sky.ppm"}));
  expect_default_ppm(dest);
  EXPECT_EQ(read_file(other), precious);
  EXPECT_EQ(fs::hard_link_count(dest), 1u);
}

// ---------------------------------------------------------------- symbolic links

// A dangling link: the file it names is created, as `>` does; the link stays.
TEST(SymbolicLink, DanglingCreatesTheFileItNames) {
  cli_sandbox box;
  fs::create_directory(box.work() / "real");
  fs::create_symlink("real/missing.ppm", box.work() / "d.ppm");
  expect_success(box.run({"-o", "d.ppm"}));
  EXPECT_TRUE(fs::is_symlink(box.work() / "d.ppm"));
  EXPECT_EQ(fs::read_symlink(box.work() / "d.ppm"), "real/missing.ppm");
  expect_default_ppm(box.work() / "real" / "missing.ppm");
}

// A chain of links, relative to each link's own directory.
TEST(SymbolicLink, ChainReplacesTheLastFile) {
  cli_sandbox box;
  fs::create_directories(box.work() / "a" / "b");
  write_file(box.work() / "a" / "b" / "real.ppm", precious);
  fs::create_symlink("b/real.ppm", box.work() / "a" / "link2.ppm");
  fs::create_symlink("a/link2.ppm", box.work() / "link1.ppm");
  expect_success(box.run({"-o", "link1.ppm"}));
  EXPECT_TRUE(fs::is_symlink(box.work() / "link1.ppm"));
  EXPECT_TRUE(fs::is_symlink(box.work() / "a" / "link2.ppm"));
  expect_default_ppm(box.work() / "a" / "b" / "real.ppm");
}

TEST(SymbolicLink, LoopIsReported) {
  cli_sandbox box;
  fs::create_symlink("b.ppm", box.work() / "a.ppm");
  fs::create_symlink("a.ppm", box.work() / "b.ppm");
  expect_runtime_error(box.run({"-o", "a.ppm"}), "a.ppm", "Too many levels of symbolic links");
  EXPECT_EQ(box.entries(), (std::vector<std::string>{"a.ppm", "b.ppm"}));
}

// ---------------------------------------------------------------- format limits

struct limit_case {
  std::vector<std::string> args;
  std::string line;
};

class FormatLimit : public ::testing::TestWithParam<limit_case> {
 protected:
  cli_sandbox box;
};

TEST_P(FormatLimit, IsAUsageErrorAndNothingIsWritten) {
  const run_result r = box.run(GetParam().args);
  expect_usage_error(r, GetParam().line);
  EXPECT_TRUE(box.entries().empty());
}

INSTANTIATE_TEST_SUITE_P(
    Encoders, FormatLimit,
    ::testing::Values(
        limit_case{{"-w", "70000", "--height", "2", "-o", "x.jpg"},
                   "--width: JPEG supports at most 65500 pixels per side, got 70000"},
        limit_case{{"-w", "2", "--height", "65501", "-o", "x.jpeg"},
                   "--height: JPEG supports at most 65500 pixels per side, got 65501"},
        limit_case{{"-w", "65500", "--aspect", "0.5", "-o", "x.jpg"},
                   "--aspect: JPEG supports at most 65500 pixels per side, got a height of 131000"},
        limit_case{{"-w", "1000001", "--height", "1", "-o", "x.png"},
                   "--width: PNG supports at most 1000000 pixels per side, got 1000001"},
        limit_case{{"-w", "1", "--height", "1000001", "--format", "png", "-o", "x.ppm"},
                   "--height: PNG supports at most 1000000 pixels per side, got 1000001"}),
    [](const auto& p) { return "case" + std::to_string(p.index); });

// Right at the limits the libraries accept the image (no library line).
TEST(FormatLimitEdge, JpegAt65500Works) {
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  cli_sandbox box;
  expect_success(box.run({"-w", "65500", "--height", "2", "-o", "x.jpg"}));
  EXPECT_GT(fs::file_size(box.work() / "x.jpg"), 0u);
}

// ---------------------------------------------------------------- free space

// A PPM's size is exact: one that cannot fit is refused before the first
// byte, with both figures, instead of filling the disk for everyone else.
TEST(FreeSpace, PpmLargerThanTheFileSystemIsRefusedUpFront) {
  cli_sandbox box;
  struct statvfs vfs {};
  ASSERT_EQ(statvfs(box.work().c_str(), &vfs), 0);
  const uint64_t free_bytes = uint64_t(geteuid() == 0 ? vfs.f_bfree : vfs.f_bavail) * vfs.f_frsize;
  const uint64_t need = 25 + uint64_t(16777216) * 16777216 * 3;  // "P6\n16777216 16777216\n255\n"
  ASSERT_LT(free_bytes, need) << "a file system with 844 TB free";
  write_file(box.work() / "huge.ppm", precious);
  const run_result r = box.run({"-w", "16777216", "--height", "16777216", "-o", "huge.ppm"});
  EXPECT_EQ(r.exit_code, 1) << how_it_ended(r);
  EXPECT_EQ(r.err.rfind("raycast: error: huge.ppm: the image needs 844424930131993 bytes (844.4 TB) "
                        "but its file system has ", 0), 0u) << r.err;
  // The free figure moves with everything else on the machine: its shape only.
  EXPECT_TRUE(std::regex_match(r.err, std::regex(".* has [0-9]+ bytes \\([0-9.]+ ([kMGTPE]B|bytes)\\) free\n")))
      << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_EQ(read_file(box.work() / "huge.ppm"), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"huge.ppm"});
}

// ---------------------------------------------------------------- terminals and pipes

// As gzip: binary data is not written to a terminal.
TEST(StandardOutputTerminal, IsRefused) {
  cli_sandbox box;
  const int master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0)
    GTEST_SKIP() << "no pseudo-terminal here: " << std::strerror(errno);
  const int slave = open(ptsname(master), O_RDWR | O_NOCTTY | O_CLOEXEC);
  ASSERT_GE(slave, 0) << std::strerror(errno);
  run_options opts;
  opts.stdout_fd = slave;
  const pid_t pid = box.start({"-o", "-"}, opts);
  close(slave);
  const run_result r = box.finish(pid);
  expect_runtime_error(r, "standard output",
                       "is a terminal; not writing binary image data to it (redirect it to a file "
                       "or a pipe)");
  fcntl(master, F_SETFL, O_NONBLOCK);
  char buf[64];
  EXPECT_LE(read(master, buf, sizeof buf), 0) << "bytes reached the terminal";
  close(master);
}

// The same for a terminal named as the output file (`-o /dev/tty`).
TEST(OutputTerminal, NamedTerminalIsRefused) {
  cli_sandbox box;
  const int master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0)
    GTEST_SKIP() << "no pseudo-terminal here: " << std::strerror(errno);
  const std::string tty = ptsname(master);
  const run_result r = box.run({"--format", "ppm", "-o", tty});
  expect_runtime_error(r, tty,
                       "is a terminal; not writing binary image data to it (redirect it to a file "
                       "or a pipe)");
  fcntl(master, F_SETFL, O_NONBLOCK);
  char buf[64];
  EXPECT_LE(read(master, buf, sizeof buf), 0) << "bytes reached the terminal";
  close(master);
  EXPECT_TRUE(box.entries().empty());
}

// TIFF and EXR go back to finish the file: a FIFO is refused before it is
// opened (which would wait for a reader) and nothing is written.
class Fifo : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(Fifo, SeekingFormatIsRefusedUpFront) {
  ASSERT_EQ(mkfifo((box.work() / "pipe").c_str(), 0644), 0) << std::strerror(errno);
  const std::string format = GetParam();
  const run_result r = box.run({"--format", format, "-o", "pipe"});
  expect_runtime_error(r, "pipe", std::string(format == "tif" ? "TIFF" : "EXR") +
                                      " needs a seekable file, and this is a pipe or a terminal "
                                      "(PPM, PNG and JPEG can stream)");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"pipe"});
}

INSTANTIATE_TEST_SUITE_P(Formats, Fifo, ::testing::Values("tif", "exr"),
                         [](const auto& p) { return std::string(p.param); });

// /dev/stdout on a pipe: the same, without a FIFO in the file system.
TEST(DevStdout, PipeWithTiffIsRefused) {
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  cli_sandbox box;
  int p[2];
  ASSERT_EQ(pipe2(p, O_CLOEXEC), 0);
  run_options opts;
  opts.stdout_fd = p[1];
  const pid_t pid = box.start({"--format", "tif", "-o", "/dev/stdout"}, opts);
  close(p[1]);
  std::string got;
  char buf[4096];
  for (ssize_t n; (n = read(p[0], buf, sizeof buf)) > 0;) got.append(buf, size_t(n));
  close(p[0]);
  const run_result r = box.finish(pid);
  EXPECT_EQ(r.exit_code, 1) << how_it_ended(r);
  EXPECT_EQ(r.err, "raycast: error: /dev/stdout: TIFF needs a seekable file, and this is a pipe or a "
                   "terminal (PPM, PNG and JPEG can stream)\n");
  EXPECT_TRUE(got.empty()) << got.size() << " bytes reached the pipe";
}

// PNG and JPEG write in order, so they stream through a pipe, byte for byte
// what they write to a file.
class StreamingFormat : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(StreamingFormat, ThroughAPipeMatchesTheFile) {
  const std::string format = GetParam();
  expect_success(box.run({"-q", "-o", "file." + format}));
  int p[2];
  ASSERT_EQ(pipe2(p, O_CLOEXEC), 0);
  run_options opts;
  opts.stdout_fd = p[1];
  const pid_t pid = box.start({"-q", "--format", format, "-o", "/dev/stdout"}, opts);
  close(p[1]);
  std::string got;
  char buf[4096];
  for (ssize_t n; (n = read(p[0], buf, sizeof buf)) > 0;) got.append(buf, size_t(n));
  close(p[0]);
  const run_result r = box.finish(pid);
  EXPECT_EQ(r.exit_code, 0) << how_it_ended(r) << ": " << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(got, read_file(box.work() / ("file." + format)));
}

INSTANTIATE_TEST_SUITE_P(Formats, StreamingFormat, ::testing::Values("png", "jpg"),
                         [](const auto& p) { return std::string(p.param); });

}  // namespace
