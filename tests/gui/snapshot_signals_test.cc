// `taebp snapshot` (issue 32, items 9 and 14): a time beyond the scenario's
// end and a zoom that shows less than a car are refused at once; SIGTERM
// under xvfb-run ends the whole group (xvfb-run, Xvfb, the re-executed
// taebp, sumo-gui) and removes xvfb-run's temporary folder.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::Process;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";

bool OnPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// The processes whose environment holds `text` (our TMPDIR: xvfb-run's
// children, sumo-gui).
std::vector<std::string> ProcessesWith(const std::string& text) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string env = ReadText(e.path() / "environ");
    if (env.find(text) != std::string::npos)
      found.push_back(pid + " " + ReadText(e.path() / "comm"));
  }
  return found;
}

TEST(Snapshot, ATimeBeyondTheEndAndAZoomBelowACarAreRefusedAtOnce) {
  if (!OnPath("sumo-gui")) GTEST_FAIL() << "sumo-gui is missing (Debian package sumo)";
  TempDir tmp;
  const std::string png = (tmp.path() / "x.png").string();
  const auto start = std::chrono::steady_clock::now();
  CliResult r = taebp::test::RunProgram(kCli, {"snapshot", kPaper, "--out", png, "--at", "100000"});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("--at 100000 s is beyond the scenario's end")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.duration")) << r.Describe();
  r = taebp::test::RunProgram(kCli, {"snapshot", kPaper, "--out", png, "--zoom", "1e9"});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("--zoom 1e+09: the view would be")) << r.Describe();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));
  EXPECT_FALSE(fs::exists(png));
}

TEST(Snapshot, SigtermUnderXvfbEndsSumoGuiXvfbAndTheirTemporaryFolder) {
  if (!OnPath("sumo-gui")) GTEST_FAIL() << "sumo-gui is missing (Debian package sumo)";
  if (!OnPath("xvfb-run")) GTEST_FAIL() << "xvfb-run is missing (Debian package xvfb)";
  TempDir tmp;
  const fs::path tmpdir = tmp.path() / "tmp";
  fs::create_directories(tmpdir);
  const std::string png = (tmp.path() / "x.png").string();
  Process p(kCli,
            {"snapshot", kPaper, "--out", png, "--at", "3000", "--set", "scenario.duration=3600"},
            [&] {
              ::unsetenv("DISPLAY");
              ::setenv("TMPDIR", tmpdir.c_str(), 1);
            });
  // sumo-gui runs once a process of the group is called so.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto gui_running = [&] {
    for (const std::string& proc : ProcessesWith("TMPDIR=" + tmpdir.string()))
      if (proc.find("sumo-gui") != std::string::npos) return true;
    return false;
  };
  while (!gui_running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(gui_running()) << p.Stderr();
  ::kill(p.pid(), SIGTERM);
  const CliResult r = p.Wait();
  EXPECT_EQ(r.exit_code, 143) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("interrupted by SIGTERM")) << r.Describe();
  std::vector<std::string> left = ProcessesWith("TMPDIR=" + tmpdir.string());
  for (int i = 0; i < 100 && !left.empty(); ++i) {  // SIGKILLed: gone within moments
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    left = ProcessesWith("TMPDIR=" + tmpdir.string());
  }
  EXPECT_THAT(left, testing::IsEmpty()) << "processes of the snapshot still running";
  EXPECT_TRUE(fs::is_empty(tmpdir)) << "xvfb-run's temporary folder left in TMPDIR";
  EXPECT_FALSE(fs::exists(png));
}

}  // namespace
