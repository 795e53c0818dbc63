// The SweepCli fixture: a small sweep config in a fresh folder and `taebp
// sweep` / `taebp merge` run through the shell as a user would.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace taebp::test {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

inline std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

class SweepCli : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/taebp_sweep_test_XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // A small sweep: 2 x 2 points (one zipped axis) x 2 seeds, two policies.
  fs::path Config(const std::string& grid = "", int replicates = 2) {
    const fs::path p = dir_ / "sweep.yaml";
    std::ofstream(p) << "scenario: {avs: 4, hvs: 4, stop_distance: 3.0, duration: 90, seed: 5}\n"
                        "model: {trust: 0.6}\n"
                        "policies: [no_trust, ta_ebp]\n"
                        "sweep:\n  replicates: " << replicates << "\n  grid:\n"
                     << (grid.empty() ? "    model.trust: [0.3, 0.9]\n"
                                        "    \"scenario.avs,scenario.hvs\": [[2, 6], [6, 2]]\n"
                                      : grid);
    return p;
  }

  // Runs a shell command line; its output goes to dir/log.txt.
  int Shell(const std::string& cmd) {
    const fs::path log = dir_ / "log.txt";
    const int st = std::system((cmd + " >" + Quote(log.string()) + " 2>&1").c_str());
    last_log_ = ReadFile(log);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  }
  int Taebp(const std::string& args) { return Shell(Quote(TAEBP_CLI) + " " + args); }
  int Sweep(const fs::path& config, const fs::path& out, const std::string& extra = "") {
    return Taebp("sweep " + Quote(config.string()) + " --out " + Quote(out.string()) +
                 " --quiet " + extra);
  }

  void ExpectSameTables(const fs::path& a, const fs::path& b) {
    for (const char* f : {"results.csv", "results.jsonl", "aggregate.csv"}) {
      ASSERT_TRUE(fs::exists(a / f)) << a / f;
      ASSERT_TRUE(fs::exists(b / f)) << b / f;
      EXPECT_EQ(ReadFile(a / f), ReadFile(b / f)) << f << " differs between " << a << " and " << b;
    }
  }

  std::vector<nlohmann::json> Journal(const fs::path& out) {
    std::vector<nlohmann::json> lines;
    std::istringstream in(ReadFile(out / "journal.jsonl"));
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
  }

  fs::path dir_;
  std::string last_log_;
};

}  // namespace taebp::test
