// Progress goes to a person at a terminal only: on a pty raycast shows the
// lesson's "Scanlines remaining" with a bar and leaves a clean line; with
// --quiet, or when standard error is not a terminal, it prints nothing.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

// Runs raycast with all three standard streams on a new pseudo-terminal and
// returns what it wrote there, and its exit code.
std::pair<std::string, int> run_on_pty(std::vector<std::string> args) {
  std::vector<std::string> cmd = raycast_test::command_for(RAYCAST_EXE);
  cmd.insert(cmd.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : cmd) argv.push_back(a.data());
  argv.push_back(nullptr);
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t n = read(master, buf, sizeof buf);
    if (n <= 0) break;  // EIO once the child has exited and closed the pty
    out.append(buf, size_t(n));
  }
  int status = 0;
  waitpid(pid, &status, 0);
  close(master);
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

TEST(Progress, ShownOnATerminalAndClearedAtTheEnd) {
  raycast_test::cli_sandbox box;
  const auto [out, rc] = run_on_pty({"-w", "2048", "-o", box.path("p.ppm")});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("Scanlines remaining: 1152"), std::string::npos) << out;
  EXPECT_NE(out.find("rendering"), std::string::npos) << out;
  EXPECT_NE(out.find("writing"), std::string::npos) << out;
  const std::string clear = "\r\033[K";
  ASSERT_GE(out.size(), clear.size());
  EXPECT_EQ(out.substr(out.size() - clear.size()), clear) << "the last thing printed clears the line";
}

TEST(Progress, QuietOnATerminalPrintsNothing) {
  raycast_test::cli_sandbox box;
  const auto [out, rc] = run_on_pty({"-q", "-w", "2048", "-o", box.path("q.ppm")});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_TRUE(out.empty()) << out;
}

TEST(Progress, NotATerminalPrintsNothing) {
  raycast_test::cli_sandbox box;
  const raycast_test::run_result r = box.run({"-w", "2048", "-o", "n.ppm"});
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace
