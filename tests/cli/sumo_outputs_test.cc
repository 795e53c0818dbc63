// SUMO's own outputs per policy (issue 17, item 16), through the built
// program as a user would: scenario.outputs {fcd, edgedata, lanedata, queue}
// land in DIR/<policy>/, one folder per policy, byte-identical for the same
// config and seed; an edgeData the user's additional file names is written
// per policy into the run folder (never into the user's folder, one policy
// overwriting the other); the network taebp generated is kept as
// DIR/network.net.xml, which SUMO loads; a rerun with fewer policies or
// outputs keeps none of the older ones; a sweep refuses scenario.outputs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;
using taebp::test::CliResult;
using taebp::test::ReadText;
using taebp::test::TempDir;

const std::string kCli = TAEBP_CLI;

CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

// Every file below `dir` by its path relative to it (the lock and the wall
// times left out).
std::set<std::string> Tree(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).string();
    // taebp's bookkeeping (the lock, the manifest of the run's files), not results.
    if (rel == ".taebp.lock" || rel == ".taebp-files" || rel == "timing.json") continue;
    out.insert(rel);
  }
  return out;
}

// A 2 x 2 grid, generated demand, an additional file of the user's that
// asks SUMO for edge means every 30 s into my_edges.xml (beside it).
fs::path WriteConfig(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "mine.add.xml")
      << "<additional>\n  <edgeData id=\"mine\" file=\"my_edges.xml\" period=\"30\"/>\n"
         "</additional>\n";
  std::ofstream(dir / "grid.yaml")
      << "scenario:\n"
         "  kind: network\n"
         "  grid: {columns: 2, rows: 2, length: 100, attach_length: 50}\n"
         "  demand: {flow: 300}\n"
         "  av_share: 0.5\n"
         "  duration: 120\n"
         "  warmup: 20\n"
         "  additional: [mine.add.xml]\n"
         "  outputs: {fcd: true, edgedata: true, lanedata: true, queue: true}\n"
         "policies: [sumo_native, ta_ebp]\n";
  return dir / "grid.yaml";
}

TEST(SumoOutputs, PerPolicyFoldersTheUsersEdgeDataAndTheNetworkThatRan) {
  TempDir tmp;
  const fs::path config = WriteConfig(tmp.path() / "cfg");
  const fs::path out = tmp.path() / "out", again = tmp.path() / "again";
  CliResult r = RunCli({"run", config.string(), "--out", out.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const std::set<std::string> expected = {
      "collisions.csv", "config.yaml", "encounters.csv", "junctions.csv", "network.net.xml",
      "summary.json",
      "sumo_native", "sumo_native/edgedata.xml", "sumo_native/fcd.xml",
      "sumo_native/lanedata.xml", "sumo_native/my_edges.xml", "sumo_native/queue.xml",
      "ta_ebp", "ta_ebp/edgedata.xml", "ta_ebp/fcd.xml", "ta_ebp/lanedata.xml",
      "ta_ebp/my_edges.xml", "ta_ebp/queue.xml"};
  EXPECT_EQ(Tree(out), expected);
  // The user's folder gained nothing (SUMO would write my_edges.xml there).
  EXPECT_EQ(Tree(tmp.path() / "cfg"), (std::set<std::string>{"grid.yaml", "mine.add.xml"}));
  // Each policy's own: the controller moved vehicles SUMO alone would not.
  const std::string native_fcd = ReadText(out / "sumo_native/fcd.xml");
  const std::string ta_fcd = ReadText(out / "ta_ebp/fcd.xml");
  EXPECT_THAT(native_fcd, HasSubstr("<fcd-export"));
  EXPECT_THAT(native_fcd, HasSubstr("<vehicle id="));
  EXPECT_NE(native_fcd, ta_fcd);
  // The user's edgeData every 30 s from 0 to 120 s: four intervals.
  const std::string mine = ReadText(out / "ta_ebp/my_edges.xml");
  std::size_t intervals = 0;
  for (std::size_t at = 0; (at = mine.find("<interval ", at)) != std::string::npos; ++at)
    ++intervals;
  EXPECT_EQ(intervals, 4u) << mine.substr(0, 600);
  // scenario.outputs' edge means: one interval, the measured time (from the
  // warm-up's end).
  EXPECT_THAT(ReadText(out / "ta_ebp/edgedata.xml"), HasSubstr("begin=\"20.00\""));
  // Same config and seed: the same bytes (SUMO's dated header replaced).
  r = RunCli({"run", config.string(), "--out", again.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  for (const std::string& f : expected)
    if (!fs::is_directory(out / f)) { EXPECT_EQ(ReadText(out / f), ReadText(again / f)) << f; }
  EXPECT_THAT(native_fcd, ::testing::Not(HasSubstr("generated on")));
  // The network that ran (netgenerate's grid) is the one in the folder, and
  // SUMO loads it.
  const int loads = std::system(("sumo -n " + (out / "network.net.xml").string() +
                                 " --end 1 --no-step-log > /dev/null 2>&1").c_str());
  EXPECT_EQ(loads, 0);
  // A rerun with fewer policies and outputs keeps none of the older ones
  // (a user's own file stays).
  std::ofstream(out / "notes.txt") << "mine";
  r = RunCli({"run", config.string(), "--out", out.string(), "--quiet", "--set",
              "policies=[ta_ebp]", "--set",
              "scenario.outputs={fcd: true, edgedata: false, lanedata: false, queue: false}"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(Tree(out), (std::set<std::string>{"collisions.csv", "config.yaml", "encounters.csv",
                                               "junctions.csv", "network.net.xml", "notes.txt",
                                               "summary.json",
                                               "ta_ebp", "ta_ebp/fcd.xml",
                                               "ta_ebp/my_edges.xml"}));
}

// The user's own network, unchanged, is not copied: summary.json's config
// names it. A sweep refuses scenario.outputs (it keeps tables only).
TEST(SumoOutputs, TheUsersNetworkIsNotCopiedAndASweepRefusesOutputs) {
  TempDir tmp;
  const fs::path config = WriteConfig(tmp.path() / "cfg");
  const fs::path first = tmp.path() / "first";
  CliResult r = RunCli({"run", config.string(), "--out", first.string(), "--quiet", "--set",
                        "policies=[sumo_native]"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const fs::path net = tmp.path() / "cfg" / "own.net.xml";
  fs::copy_file(first / "network.net.xml", net);
  const fs::path out = tmp.path() / "out";
  r = RunCli({"run", config.string(), "--out", out.string(), "--quiet", "--set",
              "policies=[sumo_native]", "--set", "scenario.grid=null", "--set",
              "scenario.network=own.net.xml"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_FALSE(fs::exists(out / "network.net.xml"));
  EXPECT_TRUE(fs::exists(out / "sumo_native" / "fcd.xml"));
  std::ofstream(tmp.path() / "cfg" / "sweep.yaml")
      << ReadText(config) << "sweep: {replicates: 1, grid: {scenario.av_share: [0.5]}}\n";
  r = RunCli({"sweep", (tmp.path() / "cfg" / "sweep.yaml").string(), "--out",
              (tmp.path() / "sweep").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr("scenario.outputs"));
  EXPECT_THAT(r.err, HasSubstr("taebp run"));
}

}  // namespace
