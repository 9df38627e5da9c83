// The `raycast` executable's output files: the formats it refuses, the
// destinations it writes (device nodes, symlinks, the longest name) and that a
// failed write never leaves a damaged file or a temporary behind. (Options and
// the picture they give are test_cli.cpp's.)
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <chrono>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"

namespace {

using raycast_test::cli_sandbox;
using raycast_test::count_lines;
using raycast_test::have_image_module;
using raycast_test::read_file;
using raycast_test::run_options;
using raycast_test::run_result;
using raycast_test::write_file;

namespace fs = std::filesystem;

using raycast_test::contains;
using raycast_test::expect_one_error_line;

class Cli : public ::testing::Test {
 protected:
  cli_sandbox box;
};

// However the format is unsupported, the message lists the supported ones.
TEST_F(Cli, EveryUnsupportedFormatListsTheSupportedOnes) {
  const std::vector<std::vector<std::string>> ways = {
      {"-o", "out.bmp"}, {"-o", "out"},  {"-o", "out.tar.gz"}, {"-o", "out.png.bak"},
      {"-o", "dir.png/out"}, {"-o", "out.png", "--format", "gif"}, {"-o", "out."}};
  for (const auto& args : ways) {
    const run_result r = box.run(args);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    for (const char* f : {"png", "ppm", "jpg", "tif", "exr"})
      EXPECT_TRUE(contains(r.err, f)) << f << " missing from: " << r.err;
  }
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(Cli, UnknownExtensionListsTheSupportedOnes) {
  const run_result r = box.run({"-o", "out.bmp"});
  EXPECT_EQ(r.exit_code, 2);
  for (const char* ext : {".png", ".ppm", ".jpg", ".tif", ".exr"})
    EXPECT_TRUE(contains(r.err, ext)) << ext << " missing from: " << r.err;
}

// A name as long as the file system takes (255 bytes here) is written: the
// temporary's own name, longer by its prefix and suffix, is cut to fit.
TEST_F(Cli, TheLongestFileNameIsWritten) {
  const long name_max = pathconf(box.work().c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 8);
  for (const char* ext : {".ppm", ".png"}) {
    if (std::string(ext) == ".png" && !have_image_module()) continue;
    const std::string name = std::string(size_t(name_max) - 4, 'n') + ext;
    for (int twice = 0; twice < 2; ++twice) {  // created, then replaced
      const run_result r = box.run({"-w", "16", "-o", box.path(name)});
      EXPECT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(box.entries(), std::vector<std::string>{name});
    }
    fs::remove(box.work() / name);
  }
}

TEST_F(Cli, UsageErrorLeavesAnExistingFileIntact) {
  write_file(box.work() / "out.png", "precious");
  const run_result r = box.run({"--width", "0", "-o", box.path("out.png")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(read_file(box.work() / "out.png"), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"out.png"});
}

// ---------------------------------------------------------------- unwritable destinations

TEST_F(Cli, MissingDirectoryExitsOneNamingTheFile) {
  const std::string dest = box.path("missing_dir/a.png");
  const run_result r = box.run({"-o", dest});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_TRUE(box.entries().empty());
}

TEST_F(Cli, DestinationThatIsADirectoryExitsOne) {
  fs::create_directory(box.work() / "a_directory_that_exists");
  const std::string dest = box.path("a_directory_that_exists");
  const run_result r = box.run({"-o", dest, "--format", "png"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_TRUE(fs::is_directory(dest));
  EXPECT_EQ(box.entries(), std::vector<std::string>{"a_directory_that_exists"});
}

TEST_F(Cli, ReadOnlyDirectoryExitsOne) {
  const fs::path dir = box.work() / "read_only";
  fs::create_directory(dir);
  ASSERT_EQ(chmod(dir.c_str(), 0555), 0);
  run_options opts;
  if (access(dir.c_str(), W_OK) == 0) {
    if (geteuid() != 0) GTEST_SKIP() << "a 0555 directory is still writable here";
    // Root writes anywhere: run the CLI as nobody, whom the mode does stop.
    opts.run_as = std::pair<uid_t, gid_t>{65534, 65534};
    box.open_to_others();
  }
  const std::string dest = (dir / "a.png").string();
  const run_result r = box.run({"-o", dest}, opts);
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_EQ(box.entries(), std::vector<std::string>{"read_only"});
}

// /proc refuses new files even to root.
TEST_F(Cli, DirectoryNoOneCanWriteToExitsOne) {
  const std::string dest = "/proc/raycast-test-sky.png";
  const run_result r = box.run({"-o", dest});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, dest);
  EXPECT_FALSE(fs::exists(dest));
}

TEST_F(Cli, DevFullExitsOne) {
  // A device is written in place, never replaced (even where /dev is writable):
  // see DeviceNodeDestinationIsWrittenNotReplaced, on a node of our own.
  const run_result r = box.run({"-o", "/dev/full", "--format", "ppm"});
  EXPECT_EQ(r.exit_code, 1);
  expect_one_error_line(r, "/dev/full");
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

// A destination that is a character device (here a node of /dev/full's
// device, 1:7, in the temporary directory) is written to, not replaced by a
// regular file: `raycast -o /dev/full` as root must not destroy /dev/full.
TEST_F(Cli, DeviceNodeDestinationIsWrittenNotReplaced) {
  const fs::path node = box.work() / "full";
  if (mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0)
    GTEST_SKIP() << "cannot create a device node here: " << std::strerror(errno);
  const run_result r = box.run({"-o", node.string(), "--format", "ppm"});
  struct stat st {};
  ASSERT_EQ(stat(node.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced by a regular file of "
                                   << st.st_size << " bytes";
  EXPECT_EQ(r.exit_code, 1) << "writing to a full device must fail";
  expect_one_error_line(r, node.string());
}

// Through a symbolic link the file it names is replaced (the link stays), and a
// replaced file keeps its permissions.
TEST_F(Cli, SymlinkDestinationReplacesTargetAndKeepsMode) {
  write_file(box.work() / "real.ppm", "precious");
  ASSERT_EQ(chmod((box.work() / "real.ppm").c_str(), 0600), 0);
  fs::create_symlink("real.ppm", box.work() / "link.ppm");
  const run_result r = box.run({"-o", box.path("link.ppm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(box.work() / "link.ppm"));
  struct stat st {};
  ASSERT_EQ(stat((box.work() / "real.ppm").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(st.st_size, 270015);  // header + 400 x 225 x 3
}

// ---------------------------------------------------------------- failures while writing

class CliWriteFailure : public Cli, public ::testing::WithParamInterface<const char*> {};

// A write that fails half-way (the file size limit stands in for a full disk)
// exits 1 naming the file, removes the temporary file and leaves the previous
// file at the destination exactly as it was.
TEST_P(CliWriteFailure, KeepsTheExistingFileAndRemovesTheTemporary) {
  const std::string name = std::string("out.") + GetParam();
  write_file(box.work() / name, "precious");
  run_options opts;
  opts.file_size_limit = 1024;
  const run_result r = box.run({"-o", box.path(name)}, opts);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  expect_one_error_line(r, box.path(name));
  EXPECT_EQ(read_file(box.work() / name), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{name});
}

std::string extension_name(const ::testing::TestParamInfo<const char*>& p) { return p.param; }

INSTANTIATE_TEST_SUITE_P(Formats, CliWriteFailure,
                         ::testing::Values("ppm", "png", "jpg", "tif", "exr"), extension_name);

TEST_F(Cli, StandardOutputWriteFailureExitsOne) {
  run_options opts;
  opts.stdout_path = "/dev/full";
  const run_result r = box.run({"-o", "-"}, opts);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_TRUE(contains(r.err, "standard output")) << r.err;
  EXPECT_TRUE(box.entries().empty());
}

// SIGTERM during a write removes the temporary file and leaves the previous
// file intact.
TEST_F(Cli, TerminationRemovesTheTemporaryFile) {
  // PNG: its encoding runs long enough to be caught mid-write.
  if (!have_image_module()) GTEST_SKIP() << "built without the image module";
  write_file(box.work() / "big.png", "precious");
  // Large enough that encoding runs for seconds; we stop it at once.
  const pid_t pid = box.start({"--width", "8192", "--height", "8192", "-o", box.path("big.png")});
  bool seen = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    seen = box.output_in_progress(pid).has_value();
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  kill(pid, SIGTERM);
  const run_result r = box.finish(pid);  // also checks that no temporary file remains
  ASSERT_TRUE(seen) << "the file being written never appeared";
  EXPECT_EQ(r.signal, SIGTERM) << "exit code " << r.exit_code << ": " << r.err;
  EXPECT_EQ(read_file(box.work() / "big.png"), "precious");
  EXPECT_EQ(box.entries(), std::vector<std::string>{"big.png"});
}

}  // namespace
