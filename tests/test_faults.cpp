// The fault matrix: what `raycast` does when the world fails under it — a full
// file system, a full device, a destination it cannot create, a standard output
// that is closed or whose reader goes away, a signal half-way through.
//
// Every runtime failure must look the same: exit status 1 (not a signal, not
// libjpeg's exit()), exactly one line "raycast: error: <file>: <cause>" on
// standard error, no temporary ".name.XXXXXX" left behind (cli_sandbox::finish
// checks that after every run) and a file that was at the destination before
// byte-for-byte as it was.
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::count_lines;
using raycast_test::expect_runtime_error;
using raycast_test::how_it_ended;
using raycast_test::precious;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;
using raycast_test::write_file;

namespace fs = std::filesystem;

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string format_name(const ::testing::TestParamInfo<const char*>& p) { return p.param; }

// ---------------------------------------------------------------- a full file system

struct disk_case {
  const char* format;
  int width, height;
};

void PrintTo(const disk_case& c, std::ostream* os) {
  *os << c.format << " " << c.width << "x" << c.height;
}

// A 64 KiB tmpfs mounted for the test on <sandbox>/work/fs. Mounting needs root
// (CAP_SYS_ADMIN); elsewhere the test is skipped with the reason.
class FullFilesystem : public ::testing::TestWithParam<disk_case> {
 protected:
  void SetUp() override {
    mnt_ = box.work() / "fs";
    fs::create_directory(mnt_);
    if (geteuid() != 0)
      GTEST_SKIP() << "mounting a tmpfs needs root; this test runs as uid " << geteuid();
    // A mount namespace of our own, where we can have one: no one else sees the
    // mount, and it goes away with this process even if it dies before TearDown.
    if (unshare(CLONE_NEWNS) == 0) mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr);
    if (mount("raycast-test", mnt_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV | MS_NOEXEC,
              "size=64k,mode=0755") != 0)
      GTEST_SKIP() << "cannot mount a 64 KiB tmpfs on " << mnt_ << ": " << std::strerror(errno);
    mounted_ = true;
  }

  void TearDown() override {
    if (mounted_ && umount2(mnt_.c_str(), MNT_DETACH) != 0)
      ADD_FAILURE() << "umount " << mnt_ << ": " << std::strerror(errno);
  }

  uint64_t free_bytes() const {
    struct statvfs st {};
    if (statvfs(mnt_.c_str(), &st) != 0) return ~uint64_t{0};
    return uint64_t(st.f_bavail) * st.f_frsize;
  }

  // Writes <fs>/filler until the file system refuses another byte. tmpfs hands
  // out whole pages, so "a few hundred bytes free" is not a state it can be
  // in: it ends with nothing free at all.
  void fill_up() {
    const int fd = open((mnt_ / "filler").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0) << std::strerror(errno);
    const std::string page(4096, 'x');
    for (;;) {
      const ssize_t n = write(fd, page.data(), page.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
    }
    close(fd);
  }

  cli_sandbox box;
  fs::path mnt_;
  bool mounted_ = false;
};

TEST_P(FullFilesystem, ExitsOneKeepsTheOldFileAndLeavesNoTemporary) {
  const disk_case& c = GetParam();
  const std::string name = std::string("sky.") + c.format;
  const fs::path dest = mnt_ / name;
  write_file(dest, precious);
  ASSERT_EQ(read_file(dest), precious);
  std::vector<std::string> want_names{name};
  if (c.width * c.height <= 64 * 64) {
    // A tiny image fits anywhere but on a file system with nothing free.
    ASSERT_NO_FATAL_FAILURE(fill_up());
    ASSERT_EQ(free_bytes(), 0u) << "the filler did not fill the file system";
    want_names.insert(want_names.begin(), "filler");
  } else {
    // Every format's 1920x1080 file is larger than 64 KiB (PNG ~88 kB, TIFF
    // ~79 kB, JPEG ~95 kB, PPM 6.2 MB, EXR 9.7 MB): the disk fills part-way.
    ASSERT_LT(free_bytes(), 64u * 1024);
  }

  const run_result r = box.run({"--width", std::to_string(c.width), "--height",
                                std::to_string(c.height), "-o", dest.string()});
  if (std::string(c.format) == "ppm") {
    // A PPM's size is known before the first byte: refused up front, with
    // both figures (FreeSpace below has the exact line).
    EXPECT_EQ(r.exit_code, 1) << how_it_ended(r);
    EXPECT_EQ(r.err.rfind("raycast: error: " + dest.string() + ": the image needs ", 0), 0u) << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  } else {
    // For JPEG this is the containment of libjpeg's error exit: that would
    // print its own message and exit() with the temporary file still on the
    // disk.
    expect_runtime_error(r, dest.string(), "No space left on device");
  }
  EXPECT_EQ(read_file(dest), precious) << "the old file was damaged";
  EXPECT_EQ(names_in(mnt_), want_names);
}

const disk_case disk_cases[] = {
    {"png", 8, 8},    {"ppm", 8, 8},    {"jpg", 8, 8},    {"tif", 8, 8},    {"exr", 8, 8},
    {"png", 1920, 1080}, {"ppm", 1920, 1080}, {"jpg", 1920, 1080}, {"tif", 1920, 1080},
    {"exr", 1920, 1080},
};

std::string disk_case_name(const ::testing::TestParamInfo<disk_case>& p) {
  return std::string(p.param.format) + "_" + std::to_string(p.param.width) + "x" +
         std::to_string(p.param.height);
}

INSTANTIATE_TEST_SUITE_P(Formats, FullFilesystem, ::testing::ValuesIn(disk_cases), disk_case_name);

// ---------------------------------------------------------------- /dev/full

// A device is written in place (no temporary file, no rename). PNG, TIFF and
// EXR write with pwrite, which /dev/full fails with ENOSPC like write.
class DevFull : public ::testing::TestWithParam<const char*> {
 protected:
  cli_sandbox box;
};

TEST_P(DevFull, ExitsOneWithOneLineNamingTheDevice) {
  struct stat st {};
  if (stat("/dev/full", &st) != 0 || !S_ISCHR(st.st_mode))
    GTEST_SKIP() << "no /dev/full character device here";
  const run_result r = box.run({"-o", "/dev/full", "--format", GetParam()});
  expect_runtime_error(r, "/dev/full", "No space left on device");
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full is no longer a device";
  EXPECT_TRUE(box.entries().empty());
}

INSTANTIATE_TEST_SUITE_P(Formats, DevFull, ::testing::Values("png", "ppm", "exr", "jpg", "tif"),
                         format_name);

// ---------------------------------------------------------------- destinations that cannot be made
// (test_cli.cpp has the PNG cases of a missing directory and a directory as
// destination, and a read-only directory without an old file.)

class Unwritable : public ::testing::TestWithParam<const char*> {
 protected:
  std::string name() const { return std::string("sky.") + GetParam(); }
  cli_sandbox box;
};

TEST_P(Unwritable, MissingDirectory) {
  const std::string dest = box.path("no_such_dir/" + name());
  expect_runtime_error(box.run({"-o", dest}), dest, "No such file or directory");
  EXPECT_TRUE(box.entries().empty());
}

TEST_P(Unwritable, ParentIsAFile) {
  write_file(box.work() / "plain_file", precious);
  const std::string dest = box.path("plain_file/" + name());
  expect_runtime_error(box.run({"-o", dest}), dest, "Not a directory");
  EXPECT_EQ(read_file(box.work() / "plain_file"), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"plain_file"});
}

// The destination's name, extension and all, is a directory.
TEST_P(Unwritable, DestinationIsADirectory) {
  fs::create_directory(box.work() / name());
  write_file(box.work() / name() / "inside", precious);
  const std::string dest = box.path(name());
  expect_runtime_error(box.run({"-o", dest}), dest, "Is a directory");
  EXPECT_EQ(read_file(box.work() / name() / "inside"), precious);
  EXPECT_EQ(box.entries(), (std::vector<std::string>{name(), name() + "/inside"}));
}

// An old file in a directory we may not write: refused, and the file stays.
TEST_P(Unwritable, ReadOnlyDirectoryKeepsTheOldFile) {
  const fs::path dir = box.work() / "read_only";
  fs::create_directory(dir);
  write_file(dir / name(), precious);
  ASSERT_EQ(chmod(dir.c_str(), 0555), 0);
  run_options opts;
  if (access(dir.c_str(), W_OK) == 0) {
    if (geteuid() != 0) GTEST_SKIP() << "a 0555 directory is still writable here";
    // Root writes anywhere: run as nobody, whom the mode does stop.
    opts.run_as = std::pair<uid_t, gid_t>{65534, 65534};
    box.open_to_others();
  }
  const std::string dest = (dir / name()).string();
  expect_runtime_error(box.run({"-o", dest}, opts), dest, "Permission denied");
  EXPECT_EQ(read_file(dir / name()), precious);
  EXPECT_EQ(box.entries(), (std::vector<std::string>{"read_only", "read_only/" + name()}));
}

// A file name can hold any byte but '/' and NUL; the error is still one line,
// the control character written as \xNN.
TEST(UnwritableName, ALineBreakInTheNameStaysOneLine) {
  cli_sandbox box;
  const std::string dest = box.path("no_such\ndir/sky.ppm");
  expect_runtime_error(box.run({"-o", dest}), box.path("no_such\\x0adir/sky.ppm"),
                       "No such file or directory");
  EXPECT_TRUE(box.entries().empty());
}

INSTANTIATE_TEST_SUITE_P(Formats, Unwritable, ::testing::Values("png", "ppm", "jpg", "tif", "exr"),
                         format_name);

// ---------------------------------------------------------------- standard output
//
// Decided behaviour: SIGPIPE is ignored, so a reader that goes away is a write
// error like any other — exit 1 and "raycast: error: standard output: Broken
// pipe" — never a silent death by SIGPIPE, never success. A closed standard
// output (`>&-`) is held open read-only on /dev/null by raycast, so nothing it
// opens later takes descriptor 1, and writing there fails with EBADF.

class StandardOutput : public ::testing::Test {
 protected:
  cli_sandbox box;
};

TEST_F(StandardOutput, ClosedIsBadFileDescriptor) {
  run_options opts;
  opts.close_stdout = true;
  const run_result r = box.run({"-o", "-"}, opts);
  expect_runtime_error(r, "standard output", "Bad file descriptor");
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(StandardOutput, ClosedDoesNotDisturbAFileRender) {
  run_options opts;
  opts.close_stdout = true;
  const run_result r = box.run({"-o", "sky.ppm"}, opts);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(fs::file_size(box.work() / "sky.ppm"), 270015u);  // header + 400 x 225 x 3
  EXPECT_EQ(box.entries(), std::vector<std::string>{"sky.ppm"});
}

TEST_F(StandardOutput, VersionToAClosedOutputFails) {
  run_options opts;
  opts.close_stdout = true;
  const run_result r = box.run({"--version"}, opts);
  expect_runtime_error(r, "standard output", "Bad file descriptor");
}

// A pipe whose reader takes `keep` bytes and closes its end, as `head -c`.
run_result run_into_short_reader(const cli_sandbox& box, const std::vector<std::string>& args,
                                 size_t keep, std::string& got) {
  int p[2];
  if (pipe2(p, O_CLOEXEC) != 0) throw std::runtime_error(std::strerror(errno));
  if (keep == 0) close(p[0]);  // gone before the first byte
  run_options opts;
  opts.stdout_fd = p[1];
  const pid_t pid = box.start(args, opts);
  close(p[1]);
  if (keep > 0) {
    got.resize(keep);
    size_t have = 0;
    while (have < keep) {
      const ssize_t n = read(p[0], got.data() + have, keep - have);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      have += size_t(n);
    }
    got.resize(have);
    close(p[0]);
  }
  return box.finish(pid);
}

TEST_F(StandardOutput, ReaderThatStopsEarlyIsBrokenPipe) {
  std::string got;
  // 1920 x 1080 x 3 bytes: far more than a pipe holds.
  const run_result r = run_into_short_reader(box, {"--width", "1920", "-o", "-"}, 10, got);
  EXPECT_EQ(got, "P6\n1920 10");
  expect_runtime_error(r, "standard output", "Broken pipe");
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(StandardOutput, ReaderGoneBeforeTheFirstByteIsBrokenPipe) {
  std::string got;
  const run_result r = run_into_short_reader(box, {"-o", "-"}, 0, got);
  expect_runtime_error(r, "standard output", "Broken pipe");
}

TEST_F(StandardOutput, HelpToAReaderThatIsGoneFails) {
  std::string got;
  const run_result r = run_into_short_reader(box, {"--help"}, 0, got);
  expect_runtime_error(r, "standard output", "Broken pipe");
}

// ---------------------------------------------------------------- signals

struct signal_case {
  const char* name;
  int sig;
  const char* format;
  // 0: signal as soon as the temporary file exists (loading the image module,
  // rendering the first band); otherwise once this many bytes reached it
  // (encoding and writing).
  uintmax_t after_bytes;
};

void PrintTo(const signal_case& c, std::ostream* os) { *os << c.name; }

class Signal : public ::testing::TestWithParam<signal_case> {
 protected:
  cli_sandbox box;
};

// A long job (16384 x 9216: seconds of rendering and encoding) stopped by the
// signal: the process dies of that signal, the temporary file is gone and the
// old file is as it was.
TEST_P(Signal, RemovesTheTemporaryAndKeepsTheOldFile) {
  const signal_case& c = GetParam();
  const std::string name = std::string("big.") + c.format;
  write_file(box.work() / name, precious);
  const pid_t pid = box.start({"--width", "16384", "--height", "9216", "-q", "-o", box.path(name)});
  bool reached = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!reached && std::chrono::steady_clock::now() < deadline) {
    const auto size = box.output_in_progress(pid);
    reached = size && *size >= c.after_bytes;
    if (!reached) {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        ADD_FAILURE() << "raycast ended before the signal was sent";
        return;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  kill(pid, reached ? c.sig : SIGKILL);
  const run_result r = box.finish(pid);  // also checks that no temporary file remains
  ASSERT_TRUE(reached) << "the file being written never reached " << c.after_bytes << " bytes";
  EXPECT_EQ(r.signal, c.sig) << how_it_ended(r) << ": " << r.err;
  EXPECT_EQ(read_file(box.work() / name), precious);
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});
}

// SIGTERM as soon as the PNG's temporary file exists: test_cli.cpp.
const signal_case signal_cases[] = {
    {"sigint_png_at_start", SIGINT, "png", 0},
    {"sigint_png_while_writing", SIGINT, "png", 256 * 1024},
    {"sigint_exr_while_writing", SIGINT, "exr", 1 << 20},
    {"sigterm_exr_while_writing", SIGTERM, "exr", 1 << 20},
    {"sigterm_ppm_while_writing", SIGTERM, "ppm", 1 << 20},
    {"sighup_tif_while_writing", SIGHUP, "tif", 256 * 1024},
};

std::string signal_case_name(const ::testing::TestParamInfo<signal_case>& p) { return p.param.name; }

INSTANTIATE_TEST_SUITE_P(Phases, Signal, ::testing::ValuesIn(signal_cases), signal_case_name);

}  // namespace
