// A result folder reruns itself (issue 26): a run of a network config that
// names its network relative to itself, started from the config's folder,
// saves a config.yaml that `taebp run DIR/config.yaml` reruns from any other
// working directory with byte-identical encounters.csv; tools/plot draws the
// folder's network map from elsewhere too. The network is the researcher's
// kind: a netgenerate grid whose dead ends netgenerate typed priority_stop
// (scenario.demand finds its fringe by topology). sumo_native plays no game:
// its per-encounter rates and theory are null in summary.json and empty in
// junctions.csv.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;
using Json = nlohmann::json;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;

// Runs `program args` with `cwd` as its working directory.
CliResult RunIn(const fs::path& cwd, const std::string& program,
                const std::vector<std::string>& args) {
  const std::string dir = cwd.string();
  return taebp::test::RunProgram(program, args, [dir] {
    if (::chdir(dir.c_str()) != 0) ::_exit(125);
  });
}

std::vector<std::string> SplitLine(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

class RerunFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    inputs_ = dir_.path() / "inputs";
    fs::create_directories(inputs_);
    // netgenerate types the grid's dead ends priority_stop like the rest.
    const std::string cmd =
        "netgenerate --grid --grid.number 3 --grid.length 120 --grid.attach-length 100 "
        "--default-junction-type priority_stop --tls.guess false "
        "--xml-validation never --output-file " +
        (inputs_ / "town.net.xml").string() + " > " + (inputs_ / "netgenerate.log").string() +
        " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << ReadText(inputs_ / "netgenerate.log");
    dir_.Write("inputs/town.yaml",
               "scenario:\n"
               "  kind: network\n"
               "  network: town.net.xml\n"
               "  demand: {flow: 300}\n"
               "  av_share: 0.5\n"
               "  duration: 240\n"
               "  warmup: 0\n"
               "  stall_action: record\n"
               "  seed: 7\n"
               "model: {prior_go: 0.2, collision_penalty: 3.0, trust: 0.6}\n"
               "policies: [sumo_native, ta_ebp]\n");
  }
  TempDir dir_{"taebp_rerun"};
  fs::path inputs_;
};

TEST_F(RerunFolder, SavedConfigRerunsFromAnotherDirectoryByteIdentical) {
  const fs::path first = dir_.path() / "first", second = dir_.path() / "second";
  const fs::path elsewhere = dir_.path() / "elsewhere";
  fs::create_directories(elsewhere);
  // From the config's folder, named relative to it (as a sweep runs its tasks).
  const CliResult a = RunIn(inputs_, kCli, {"run", "town.yaml", "--out", first.string()});
  ASSERT_EQ(a.exit_code, 0) << a.Describe();
  const std::string saved = ReadText(first / "config.yaml");
  EXPECT_THAT(saved, HasSubstr((inputs_ / "town.net.xml").string()))
      << "the saved config names its network by an absolute path";
  // From another folder: the saved config alone.
  const CliResult b =
      RunIn(elsewhere, kCli, {"run", (first / "config.yaml").string(), "--out", second.string()});
  ASSERT_EQ(b.exit_code, 0) << b.Describe();
  const std::string enc = ReadText(first / "encounters.csv");
  EXPECT_EQ(enc, ReadText(second / "encounters.csv"));
  EXPECT_EQ(ReadText(first / "junctions.csv"), ReadText(second / "junctions.csv"));
  EXPECT_EQ(saved, ReadText(second / "config.yaml")) << "the rerun's config names the same inputs";
  // The comparison means something: TA-EBP played encounters.
  EXPECT_THAT(enc, HasSubstr("\nta_ebp,")) << enc.substr(0, 400);

  // Only games have per-encounter rates: sumo_native's are null, TA-EBP's numbers.
  const Json s = Json::parse(ReadText(first / "summary.json"));
  const Json& native = s["policies"]["sumo_native"];
  const Json& ta = s["policies"]["ta_ebp"];
  ASSERT_GT(ta["encounters"].get<long>(), 0);
  EXPECT_EQ(native["encounters"], 0);
  for (const char* k : {"collision_rate", "collision_rate_lo", "collision_rate_hi", "dc_rate",
                        "dc_rate_lo", "dc_rate_hi", "theory_collision_rate", "theory_dc_rate",
                        "theory_nudge_rate", "theory_av_first_rate",
                        "theory_given_hvs_collision_rate", "theory_given_hvs_dc_rate"}) {
    EXPECT_TRUE(native.contains(k) && native[k].is_null()) << k << ": " << native.value(k, Json());
    EXPECT_TRUE(ta[k].is_number()) << k;
  }
  ASSERT_FALSE(native["junctions"].empty());
  for (const Json& j : native["junctions"])
    for (const char* k : {"collision_rate", "collision_rate_lo", "dc_rate_hi",
                          "theory_given_hvs_dc_rate"})
      EXPECT_TRUE(j[k].is_null()) << j["junction"] << " " << k;
  // junctions.csv: the same cells empty for sumo_native, filled for a junction
  // where TA-EBP met encounters.
  std::istringstream csv(ReadText(first / "junctions.csv"));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = SplitLine(line);
  auto col = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  int native_rows = 0, ta_played = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> cells = SplitLine(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    if (cells[0] == "sumo_native") {
      ++native_rows;
      for (const char* k : {"collision_rate", "collision_rate_lo", "collision_rate_hi",
                            "dc_rate", "theory_given_hvs_dc_rate"})
        EXPECT_EQ(cells[col(k)], "") << line;
    } else if (cells[col("encounters")] != "0") {
      ++ta_played;
      EXPECT_NE(cells[col("collision_rate")], "") << line;
      EXPECT_NE(cells[col("collision_rate_hi")], "") << line;
    }
  }
  EXPECT_GT(native_rows, 0);
  EXPECT_GT(ta_played, 0);
  // The printed table: a dash for the policy without a game, never 0 [0, 1].
  EXPECT_THAT(a.out, HasSubstr("- (SUMO's own logic)")) << a.out;
}

// tools/plot on the folder, run from elsewhere, finds the user's network
// (not copied into the folder: taebp ran it unchanged) and draws the map.
TEST_F(RerunFolder, PlotFindsTheNetworkFromAnotherDirectory) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-matplotlib is not installed: tools/plot cannot run";
  const fs::path first = dir_.path() / "first", elsewhere = dir_.path() / "elsewhere";
  fs::create_directories(elsewhere);
  const CliResult a = RunIn(inputs_, kCli, {"run", "town.yaml", "--out", first.string()});
  ASSERT_EQ(a.exit_code, 0) << a.Describe();
  ASSERT_FALSE(fs::exists(first / "network.net.xml")) << "the user's network is not copied";
  const CliResult p = RunIn(elsewhere, kSource + "/tools/plot", {first.string()});
  EXPECT_EQ(p.exit_code, 0) << p.Describe();
  EXPECT_THAT(p.err, ::testing::Not(HasSubstr("was not found"))) << p.Describe();
  EXPECT_TRUE(fs::is_regular_file(first / "network_map.png")) << p.Describe();
}

}  // namespace
