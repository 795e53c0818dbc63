// The taebp program's --help, run as a user would: every command documents every
// option, and a missing subcommand or argument is an error.
#include "taebp/config/policies.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/outcomes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using ::testing::HasSubstr;
using json = nlohmann::json;
using taebp::test::CliResult;

// Runs the built taebp with `args` (no shell), capturing stdout and stderr.
CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(TAEBP_CLI, args);
}

// ------------------------------------------------------------------ help

// Every subcommand and every option, listed here independently of the CLI's
// own definitions: an option dropped or left without a description fails, and
// a subcommand added to `taebp --help` without a row here fails too.
const std::map<std::string, std::vector<std::string>>& ExpectedOptions() {
  static const std::map<std::string, std::vector<std::string>> options = {
      {"theory", {"--prior", "--penalty", "--trust", "--assumed-trust", "--s-max", "--likelihood",
                  "--steepness", "--midpoint", "--noise", "--noise-scale", "--noise-bias",
                  "--noise-delta", "--json"}},
      {"solve", {"PROBLEM", "--json"}},
      {"run", {"CONFIG", "--set", "--out", "--quiet", "--paired", "--gui", "--delay"}},
      {"sweep", {"CONFIG", "--set", "--out", "--jobs", "--shard", "--list", "--quiet", "--mpi"}},
      {"merge", {"OUT", "--quiet"}},
      {"snapshot", {"CONFIG", "--out", "--at", "--set", "--policy", "--junction", "--zoom",
                    "--no-legend"}},
      {"metrics", {"--print"}},
      {"policies", {"--print"}},
      {"config", {"--reference", "--format"}},
  };
  return options;
}

// The option lines of a help text ("  -j,--jobs INT   description"): each
// option's name ("--jobs") with its description (on the same line after a gap
// of two spaces or more, or, after a long option column, on the next line).
std::map<std::string, std::string> OptionDescriptions(const std::string& help) {
  std::vector<std::string> lines;
  {
    std::istringstream in(help);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::map<std::string, std::string> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const std::size_t start = line.find_first_not_of(' ');
    if (start == std::string::npos || start > 4 || line.compare(start, 1, "-") != 0) continue;
    const std::size_t name_end = line.find(' ', start);
    std::string names = line.substr(start, name_end == std::string::npos ? std::string::npos
                                                                         : name_end - start);
    const std::size_t dashes = names.find("--");
    if (dashes == std::string::npos) continue;
    const std::string name = names.substr(dashes);
    std::string description;
    const std::size_t gap = line.find("  ", start);
    if (gap != std::string::npos && line.find_first_not_of(' ', gap) != std::string::npos)
      description = line.substr(line.find_first_not_of(' ', gap));
    else if (i + 1 < lines.size() && lines[i + 1].find_first_not_of(' ') > 8 &&
             lines[i + 1].find_first_not_of(' ') != std::string::npos)
      description = lines[i + 1].substr(lines[i + 1].find_first_not_of(' '));
    out[name] = description;
  }
  return out;
}

TEST(CliHelp, EveryCommandDocumentsEveryOption) {
  const CliResult top = RunCli({"--help"});
  ASSERT_EQ(top.exit_code, 0) << top.Describe();
  for (const std::string w : {"--help", "--version"}) EXPECT_THAT(top.out, HasSubstr(w));
  // The subcommands `taebp --help` lists: exactly those of the table above.
  std::vector<std::string> listed;
  {
    std::istringstream lines(top.out.substr(top.out.find("Subcommands:")));
    std::string line;
    std::getline(lines, line);
    while (std::getline(lines, line)) {
      std::istringstream words(line);
      std::string first;
      if (words >> first) listed.push_back(first);
    }
  }
  std::vector<std::string> expected;
  for (const auto& [command, _] : ExpectedOptions()) expected.push_back(command);
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, expected) << top.out;
  for (const auto& [command, options] : ExpectedOptions()) {
    SCOPED_TRACE(command);
    const CliResult r = RunCli({command, "--help"});
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
    EXPECT_THAT(r.out, HasSubstr("Usage:"));
    const std::map<std::string, std::string> described = OptionDescriptions(r.out);
    for (const std::string& o : options) {
      EXPECT_THAT(r.out, HasSubstr(o)) << r.out;
      if (o.rfind("--", 0) != 0) continue;  // a positional argument
      const auto it = described.find(o);
      ASSERT_NE(it, described.end()) << o << " has no line of its own:\n" << r.out;
      EXPECT_GE(it->second.size(), 4u) << o << " has no description:\n" << r.out;
    }
    // And no option the table does not know (one added without a row here).
    for (const auto& [name, _] : described) {
      if (name == "--help") continue;
      EXPECT_NE(std::find(options.begin(), options.end(), name), options.end())
          << command << " " << name << " is not in this test's table";
    }
  }
}

TEST(CliHelp, MissingSubcommandOrArgumentIsAnError) {
  EXPECT_NE(RunCli({}).exit_code, 0);
  EXPECT_NE(RunCli({"run"}).exit_code, 0);
  EXPECT_NE(RunCli({"solve"}).exit_code, 0);
  EXPECT_NE(RunCli({"bogus"}).exit_code, 0);
  const CliResult v = RunCli({"--version"});
  EXPECT_EQ(v.exit_code, 0) << v.Describe();
  EXPECT_FALSE(v.out.empty());
}

}  // namespace
