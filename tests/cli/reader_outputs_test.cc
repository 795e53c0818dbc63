// What a reader looks for, through the program (issue 44): a No Trust run's
// collisions.csv has one row per collision in collisions_total, each an
// encounter's pair or a game move as summary.json counts them; the encounters
// per hour in summary.json; a route file that holds a network, or demand
// files without any vehicle, are config errors naming the file; a network of
// one's own without `kind: network` says to set it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "csv_text.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::Lines;
using taebp::test::ReadText;
using taebp::test::SplitCsvLine;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;
const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";
const std::string kGrid = std::string(TAEBP_SOURCE_DIR) + "/configs/grid_throughput.yaml";
constexpr int kExitConfig = 2;

std::vector<std::map<std::string, std::string>> Rows(const fs::path& csv) {
  const std::vector<std::string> lines = Lines(ReadText(csv));
  const std::vector<std::string> header = SplitCsvLine(lines.at(0));
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = SplitCsvLine(lines[i]);
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    out.push_back(row);
  }
  return out;
}

TEST(ReaderOutputs, NoTrustsCollisionsCsvHasARowPerCollisionInCollisionsTotal) {
  TempDir dir;
  const fs::path out = dir.path() / "run";
  const CliResult r = taebp::test::RunProgram(
      kCli, {"run", kPaper, "--set", "scenario.duration=900", "--set", "scenario.warmup=60",
             "--set", "policies=[sumo_native, no_trust]", "--out", out.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json s = nlohmann::json::parse(ReadText(out / "summary.json"))["policies"];
  const auto rows = Rows(out / "collisions.csv");
  const auto encounters = Rows(out / "encounters.csv");
  // (av, hv) -> encounters of that pair that collided (a pair meets again on the track)
  std::map<std::pair<std::string, std::string>, long> collided;
  long collided_encounters = 0;
  for (const auto& e : encounters)
    if (e.at("policy") == "no_trust" && e.at("collision") == "1") {
      ++collided[{e.at("av"), e.at("hv")}];
      ++collided_encounters;
    }
  long total = 0, in_encounters = 0;
  for (const auto& row : rows) {
    EXPECT_GE(std::stod(row.at("time")), 60.0) << "after the warm-up only";
    if (row.at("policy") != "no_trust") continue;
    const std::string counted = row.at("counted_in");
    total += counted == "collisions" || counted == "other_collisions_game_move";
    if (counted != "collisions") continue;
    ++in_encounters;
    // An encounter's AV and HV, both in the game, at the figure-8's junction.
    EXPECT_EQ(row.at("junction"), "C") << row.at("lane");
    EXPECT_EQ(row.at("collider_in_game"), "1");
    EXPECT_EQ(row.at("victim_in_game"), "1");
    const bool av_first = row.at("collider_kind") == "av";
    EXPECT_NE(row.at("collider_kind"), row.at("victim_kind"));
    const std::pair<std::string, std::string> pair =
        av_first ? std::pair{row.at("collider"), row.at("victim")}
                 : std::pair{row.at("victim"), row.at("collider")};
    EXPECT_GT(collided[pair]--, 0) << pair.first << " " << pair.second;
  }
  const long collisions_total = s["no_trust"]["collisions_total"].get<long>();
  EXPECT_GT(collisions_total, 5) << "No Trust collides at lambda = 0.2 per encounter";
  EXPECT_EQ(total, collisions_total);
  EXPECT_EQ(in_encounters, s["no_trust"]["collisions"].get<long>());
  EXPECT_EQ(in_encounters, collided_encounters);
  // The encounters per measured hour; none for SUMO's own logic.
  const double hours = s["no_trust"]["measured_seconds"].get<double>() / 3600.0;
  EXPECT_NEAR(s["no_trust"]["encounters_per_hour"].get<double>(),
              s["no_trust"]["encounters"].get<double>() / hours, 1e-9);
  EXPECT_TRUE(s["sumo_native"]["encounters_per_hour"].is_null());
}

CliResult RunWithRoutes(const std::string& routes, const fs::path& out) {
  return taebp::test::RunProgram(
      kCli, {"run", kGrid, "--set", "scenario.grid.columns=2", "--set", "scenario.grid.rows=2",
             "--set", "scenario.duration=60", "--set", "scenario.warmup=0", "--set",
             "scenario.demand=null", "--set",
             "scenario.routes=[" + routes + "]", "--set", "policies=[ta_ebp]", "--out",
             out.string()});
}

TEST(ReaderOutputs, ANetworkGivenAsRoutesIsAConfigErrorNamingIt) {
  TempDir dir;
  const std::string net = (fs::path(kCli).parent_path() / "sumo_net" / "figure8.net.xml").string();
  ASSERT_TRUE(fs::is_regular_file(net)) << net;
  const CliResult r = RunWithRoutes(net, dir.path() / "out");
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.routes: '" + net + "' holds a SUMO network (<net>)"))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("give a network as scenario.network")) << r.Describe();
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(ReaderOutputs, DemandWithoutAnyVehicleIsAConfigErrorNamingItsFiles) {
  TempDir dir;
  const std::string routes = dir.Write(
      "types.rou.xml", "<routes>\n  <vType id=\"car\" length=\"5\"/>\n</routes>\n");
  const CliResult r = RunWithRoutes(routes, dir.path() / "out");
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.routes: no vehicle, trip, flow or person in '" + routes +
                               "'"))
      << r.Describe();
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(ReaderOutputs, AnOwnNetworkWithoutKindNetworkSaysToSetIt) {
  TempDir dir;
  const std::string net = (dir.path() / "grid.net.xml").string();
  const std::string make = "netgenerate --grid --grid.number 2 --no-turnarounds true -o " + net +
                           " > /dev/null 2>&1";
  if (std::system(make.c_str()) != 0) FAIL() << "netgenerate (Debian package sumo) failed";
  const CliResult r = taebp::test::RunProgram(
      kCli, {"run", kPaper, "--set", "scenario.network=" + net, "--out",
             (dir.path() / "out").string()});
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("not a figure-8 network")) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("set scenario.kind: network")) << r.Describe();
}

// Issue 43: a junction where no game can ever form is named, in
// junctions.csv (game_pairs 0) and in the run's warnings. A spider network of
// two-way stops: the five junctions of its inner ring have one stop-controlled
// approach each, so without the major-road game no two stop lines conflict.
TEST(ReaderOutputs, JunctionsThatCanHostNoGameAreNamed) {
  TempDir dir;
  const std::string net = (dir.path() / "spider.net.xml").string();
  const std::string trips = (dir.path() / "trips.rou.xml").string();
  const std::string make =
      "netgenerate --spider --spider.arm-number 5 --spider.circle-number 3 "
      "--spider.space-radius 100 --default-junction-type priority_stop --no-turnarounds -o " +
      net + " > /dev/null 2>&1 && python3 /usr/share/sumo/tools/randomTrips.py -n " + net +
      " -o " + trips + " -e 200 -p 1.5 --seed 3 > /dev/null 2>&1";
  if (std::system(make.c_str()) != 0) FAIL() << "netgenerate or randomTrips.py (sumo-tools) failed";
  const std::string cfg = dir.Write(
      "spider.yaml", "scenario: {kind: network, network: " + net + ", routes: [" + trips +
                         "], av_share: 0.5, duration: 120, warmup: 0, seed: 1}\n"
                         "policies: [ta_ebp]\n");
  const fs::path out = dir.path() / "out";
  CliResult r = taebp::test::RunProgram(
      kCli, {"run", cfg, "--set", "scenario.major_road.enabled=false", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  std::vector<std::string> none;
  int junctions = 0;
  const std::vector<std::string> lines = Lines(ReadText(out / "junctions.csv"));
  const std::vector<std::string> header = SplitCsvLine(lines.at(0));
  const auto col = std::find(header.begin(), header.end(), "game_pairs") - header.begin();
  ASSERT_LT(static_cast<std::size_t>(col), header.size());
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> cells = SplitCsvLine(lines[i]);
    ++junctions;
    if (cells.at(static_cast<std::size_t>(col)) == "0") none.push_back(cells.at(1));
  }
  EXPECT_EQ(junctions, 15);
  EXPECT_EQ(none, (std::vector<std::string>{"D1", "D2", "D3", "D4", "D5"}));
  EXPECT_THAT(r.err, HasSubstr("5 of 15 controlled junctions can host no game under these "
                               "settings (D1, D2, D3, D4, D5;"))
      << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.major_road.enabled: true")) << r.Describe();
  const auto summary = nlohmann::json::parse(ReadText(out / "summary.json"));
  EXPECT_EQ(summary["policies"]["ta_ebp"]["junctions"][0]["game_pairs"].is_number(), true);
  // With the major-road game on (the default), every junction can host one: no warning.
  r = taebp::test::RunProgram(kCli, {"run", cfg, "--out", (dir.path() / "major").string()});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("can host no game"))) << r.Describe();
}

}  // namespace
