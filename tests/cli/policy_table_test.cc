// Every policy where the program lists or recognises policies, from the one
// table (config/policies.h), through the built program:
// - a rerun into the folder of a run whose SUMO outputs sit in policy folders
//   (ta_ebp_learned, population_mean: missing from the result folder's list
//   before, so the second run refused the folder, exit 2) exits 0;
// - `taebp policies --print json` is the table, and `taebp run --help` names
//   every policy.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "test_support.h"
#include "taebp/config/policies.h"

#include <filesystem>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

TEST(PolicyTable, RerunOfEveryPolicyWithSumoOutputsIntoItsOwnFolderSucceeds) {
  TempDir tmp;
  const fs::path out = fs::path(tmp.path()) / "X";
  // The command (learned_trust.yaml: ta_ebp_learned, population_mean,
  // ta_ebp, no_trust), each policy's SUMO queue output in DIR/POLICY/.
  const std::vector<std::string> args = {
      "run", kSource + "/configs/learned_trust.yaml", "--set", "scenario.duration=120",
      "--set", "scenario.outputs={queue: true}", "--out", out.string(), "--quiet"};
  const CliResult first = RunCli(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  for (const char* p : {"ta_ebp_learned", "population_mean"})
    ASSERT_TRUE(fs::is_directory(out / p)) << p << " folder missing: the test would prove nothing";
  const CliResult second = RunCli(args);
  EXPECT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.err, ::testing::Not(HasSubstr("would replace")));
  for (const char* p : {"ta_ebp_learned", "population_mean"})
    EXPECT_TRUE(fs::is_regular_file(out / p / "queue.xml")) << p;
}

TEST(PolicyTable, PoliciesCommandPrintsTheTable) {
  const CliResult r = RunCli({"policies", "--print", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json rows = nlohmann::json::parse(r.out);
  ASSERT_EQ(rows.size(), taebp::Policies().size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const taebp::PolicyInfo& p = taebp::Policies()[i];
    EXPECT_EQ(rows[i].at("name"), p.name);
    EXPECT_EQ(rows[i].at("label"), p.label);
    EXPECT_EQ(rows[i].at("plays_game"), p.plays_game);
    EXPECT_EQ(rows[i].at("ignores").get<std::vector<std::string>>(), p.ignores);
  }
  const CliResult list = RunCli({"policies"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_EQ(list.out, taebp::PolicyListMarkdown());
  const CliResult help = RunCli({"run", "--help"});
  for (const taebp::PolicyInfo& p : taebp::Policies()) EXPECT_THAT(help.out, HasSubstr(p.name));
}

}  // namespace
