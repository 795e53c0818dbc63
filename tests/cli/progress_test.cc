// A progress line per policy inside a run (issue 17, item 12): on a terminal
// `taebp run` rewrites one line with the simulated time, the vehicles, the
// encounters and the time to go; not with --quiet, and not when stderr is a
// file or a pipe (logs stay clean).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <cerrno>
#include <string>
#include <vector>

#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";

std::vector<std::string> Args(const TempDir& dir, bool quiet) {
  std::vector<std::string> a = {"run", kPaper, "--set", "scenario.duration=600", "--set",
                                "policies=[no_ebp, ta_ebp]", "--out",
                                (dir.path() / "out").string()};
  if (quiet) a.push_back("--quiet");
  return a;
}

// Runs the program with stderr on a pseudo-terminal; what it wrote there.
std::string StderrOnATerminal(const std::vector<std::string>& args, int* exit_code) {
  int master = -1, slave = -1;
  if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "openpty failed";
  std::vector<std::string> all = {kCli};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(master);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(slave, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(slave);
  std::string text;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(master, buf, sizeof buf);
    if (n > 0) {
      text.append(buf, static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    break;  // EIO: the child closed the terminal
  }
  ::close(master);
  int status = 0;
  ::waitpid(pid, &status, 0);
  *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return text;
}

TEST(RunProgress, OnATerminalAProgressLinePerPolicy) {
  TempDir dir;
  int code = -1;
  const std::string err = StderrOnATerminal(Args(dir, false), &code);
  ASSERT_EQ(code, 0) << err;
  for (const char* p : {"no_ebp", "ta_ebp"}) {
    SCOPED_TRACE(p);
    EXPECT_THAT(err, HasSubstr(std::string("\rtaebp: ") + p)) << err;
    EXPECT_THAT(err, HasSubstr(std::string("taebp: ") + p)) << err;
  }
  EXPECT_THAT(err, HasSubstr("/600 s simulated, ")) << err;
  EXPECT_THAT(err, HasSubstr(" vehicles, ")) << err;
  EXPECT_THAT(err, HasSubstr(" encounters, ")) << err;
  EXPECT_THAT(err, HasSubstr(" s to go")) << err;
  // Each policy's own line follows its progress on a cleared line.
  EXPECT_THAT(err, HasSubstr("\r\033[Ktaebp: no_ebp       600 simulated s in")) << err;
}

TEST(RunProgress, NoneWithQuietOrWhenStderrIsNotATerminal) {
  TempDir dir;
  int code = -1;
  const std::string quiet = StderrOnATerminal(Args(dir, true), &code);
  ASSERT_EQ(code, 0) << quiet;
  EXPECT_THAT(quiet, Not(HasSubstr("s simulated,"))) << quiet;
  const taebp::test::CliResult file = taebp::test::RunProgram(kCli, Args(dir, false));
  ASSERT_EQ(file.exit_code, 0) << file.Describe();
  EXPECT_THAT(file.err, Not(HasSubstr("s simulated,"))) << file.Describe();
  EXPECT_THAT(file.err, Not(HasSubstr("\r"))) << file.Describe();
  EXPECT_THAT(file.err, HasSubstr("taebp: ta_ebp       600 simulated s in")) << file.Describe();
}

}  // namespace
