// The sweep engine's pure parts: grid expansion (zipped axes, replicates),
// spec errors naming the key, the config hash, journal parsing and tables.
// taebp-tests: sanitize (also run under the sanitizers; tests/CMakeLists.txt)
#include "taebp/sweep/plan.h"

#include "taebp/report/metrics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace taebp::sweep {
namespace {

using ::testing::HasSubstr;

const char* kBase = R"(
scenario: {avs: 8, hvs: 8, seed: 10, duration: 60}
model: {trust: 0.6}
policies: [no_trust, ta_ebp]
)";

Plan Expand(const std::string& sweep, const std::vector<std::string>& overrides = {}) {
  return ExpandSweep(std::string(kBase) + sweep, "test.yaml", overrides);
}

std::string ErrorOf(const std::string& sweep) {
  try {
    Expand(sweep);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepGrid, CartesianProductInFileOrderLastKeyFastestTimesReplicates) {
  const Plan p = Expand(R"(
sweep:
  replicates: 3
  grid:
    model.trust: [0.2, 0.8]
    scenario.cruise_speed: [3, 4, 5]
)");
  ASSERT_EQ(p.columns, (std::vector<std::string>{"model.trust", "scenario.cruise_speed"}));
  ASSERT_EQ(p.points.size(), 6u);
  EXPECT_EQ(p.points[0].values, (std::vector<std::string>{"0.2", "3"}));
  EXPECT_EQ(p.points[1].values, (std::vector<std::string>{"0.2", "4"}));
  EXPECT_EQ(p.points[3].values, (std::vector<std::string>{"0.8", "3"}));
  EXPECT_EQ(p.points[5].values, (std::vector<std::string>{"0.8", "5"}));
  ASSERT_EQ(p.tasks.size(), 18u);
  for (std::size_t i = 0; i < p.tasks.size(); ++i) {
    const Task& t = p.tasks[i];
    EXPECT_EQ(t.index, static_cast<int>(i));
    EXPECT_EQ(t.point, static_cast<int>(i / 3));
    EXPECT_EQ(t.replicate, static_cast<int>(i % 3));
    EXPECT_EQ(t.seed, 10u + i % 3);  // scenario.seed + r
  }
  EXPECT_EQ(p.TaskOverrides(p.tasks[7]),
            (std::vector<std::string>{"model.trust=0.2", "scenario.cruise_speed=5",
                                      "scenario.seed=11"}));
  EXPECT_EQ(p.points[0].policies, (std::vector<std::string>{"no_trust", "ta_ebp"}));
}

TEST(SweepGrid, ZippedKeysSplitIntoOneColumnEach) {
  const Plan p = Expand(R"(
sweep:
  replicates: 2
  grid:
    "scenario.avs, scenario.hvs": [[0, 16], [8, 8], [16, 0]]
    model.trust: [{dist: uniform, low: 0.2, high: 0.9}, 0.5]
)");
  ASSERT_EQ(p.columns, (std::vector<std::string>{"scenario.avs", "scenario.hvs", "model.trust"}));
  ASSERT_EQ(p.points.size(), 6u);
  EXPECT_EQ(p.points[0].values[0], "0");
  EXPECT_EQ(p.points[0].values[1], "16");
  EXPECT_THAT(p.points[0].values[2], HasSubstr("uniform"));
  EXPECT_EQ(p.points[5].values, (std::vector<std::string>{"16", "0", "0.5"}));
  EXPECT_EQ(p.tasks.size(), 12u);
  const auto o = p.TaskOverrides(p.tasks[11]);
  EXPECT_EQ(o[0], "scenario.avs=16");
  EXPECT_EQ(o[1], "scenario.hvs=0");
  EXPECT_EQ(o.back(), "scenario.seed=11");
}

TEST(SweepGrid, NoGridIsOnePointOfReplicates) {
  const Plan p = Expand("sweep: {replicates: 4}\n");
  EXPECT_EQ(p.points.size(), 1u);
  EXPECT_EQ(p.tasks.size(), 4u);
  EXPECT_TRUE(p.columns.empty());
}

TEST(SweepGrid, TaskOverridesAreTheUsersThenThePointsThenTheSeed) {
  const Plan p = Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.8]\n",
                        {"scenario.duration=30"});
  EXPECT_EQ(p.TaskOverrides(p.tasks[3]),
            (std::vector<std::string>{"scenario.duration=30", "model.trust=0.8",
                                      "scenario.seed=11"}));
}

TEST(SweepGrid, SweptSeedAndPoliciesAreThePoints) {
  const Plan p = Expand(R"(
sweep:
  replicates: 2
  grid:
    scenario.seed: [100, 200]
    policies: [[no_ebp], [ta_ebp, full_reveal]]
)");
  ASSERT_EQ(p.tasks.size(), 8u);
  EXPECT_EQ(p.tasks[1].seed, 101u);
  EXPECT_EQ(p.tasks[5].seed, 201u);
  EXPECT_EQ(p.points[1].policies, (std::vector<std::string>{"ta_ebp", "full_reveal"}));
}

TEST(SweepGrid, ZippedValueOfWrongLengthNamesTheKey) {
  const std::string e = ErrorOf(R"(
sweep:
  grid:
    "scenario.avs,scenario.hvs": [[0, 16], [8], [16, 0]]
)");
  EXPECT_THAT(e, HasSubstr("scenario.avs,scenario.hvs"));
  EXPECT_THAT(e, HasSubstr("value #2"));
  EXPECT_THAT(e, HasSubstr("has 1 entries, expected a list of 2 values"));
  EXPECT_THAT(ErrorOf(R"(
sweep:
  grid:
    "scenario.avs,scenario.hvs": [4, [12, 4]]
)"),
              HasSubstr("'scenario.avs,scenario.hvs': value #1 4 is not a list of 2 values"));
}

TEST(SweepGrid, EmptyValuesNameTheKey) {
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    model.trust: []\n"), HasSubstr("model.trust"));
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    model.trust: []\n"), HasSubstr("no values"));
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    model.trust: [0.5, ~]\n"),
              HasSubstr("'model.trust': value #2 is empty"));
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    \"scenario.avs,\": [[1]]\n"),
              HasSubstr("'scenario.avs,' has an empty key name"));
}

TEST(SweepGrid, OtherSpecErrors) {
  EXPECT_THAT(ErrorOf(""), HasSubstr("no 'sweep:' section"));
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    model.trust: [0.5]\n    \"scenario.avs,model.trust\": [[1, 0.2]]\n"),
              HasSubstr("key 'model.trust' appears twice"));
  EXPECT_THAT(ErrorOf("sweep: {replicates: 0}\n"), HasSubstr("sweep.replicates"));
  EXPECT_THAT(ErrorOf("sweep:\n  grid:\n    model.trust: 0.5\n"), HasSubstr("sweep.grid.model.trust"));
}

// Found by fuzzing (fuzz/regressions/sweep/latin1_comment.txt): a sweep
// config with a Latin-1 comment expanded fine and then sweep.json could not
// be written (nlohmann type_error 316). Refused up front, naming the line.
TEST(SweepGrid, ConfigThatIsNotUtf8IsRefused) {
  const std::string text = std::string("# tr\xff\xff values\n") + kBase +
                           "sweep:\n  replicates: 1\n  grid:\n    model.trust: [0.2]\n";
  try {
    ExpandSweep(text, "latin1.yaml", {});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("latin1.yaml:1: not UTF-8 text (byte 0xFF)"));
  }
  // Text the tables and sweep.json carry from elsewhere (a task's error
  // message) is written with U+FFFD instead of throwing.
  EXPECT_EQ(Dump(Json("a\xff")), "\"a\xef\xbf\xbd\"");
}

// The plan's size is bounded before anything is allocated: at most 100 000
// grid points (each point's config is checked up front) and 10 000 000 tasks
// (sweep.replicates = 1e9 used to end in std::bad_alloc).
TEST(SweepGrid, PointsAndTasksAreBounded) {
  std::string values;
  for (int i = 0; i < 400; ++i) values += (i ? ", " : "") + std::to_string(i);
  EXPECT_THAT(ErrorOf("sweep:\n  replicates: 1\n  grid:\n    scenario.seed: [" + values +
                      "]\n    scenario.min_gap: [" + values + "]\n"),
              HasSubstr("sweep.grid has more than 100000 points"));
  EXPECT_THAT(ErrorOf("sweep:\n  replicates: 1000000000\n  grid:\n    model.trust: [0.2, 0.8]\n"),
              HasSubstr("sweep.replicates = 1000000000 times 2 grid points is more than 10000000 tasks"));
}

TEST(SweepGrid, SplitFlowSequenceRespectsNestingAndQuotes) {
  std::vector<std::string> items;
  ASSERT_TRUE(SplitFlowSequence("[0, [1, 2], {a: 1, b: [3, 4]}, 'x, y', \"q\\\",\"]", &items));
  EXPECT_EQ(items, (std::vector<std::string>{"0", "[1, 2]", "{a: 1, b: [3, 4]}", "'x, y'",
                                             "\"q\\\",\""}));
  ASSERT_TRUE(SplitFlowSequence("[]", &items));
  EXPECT_TRUE(items.empty());
  EXPECT_FALSE(SplitFlowSequence("4", &items));
  EXPECT_FALSE(SplitFlowSequence("[1, [2]", &items));
}

TEST(SweepGrid, HashCoversConfigAndGridButNotReplicates) {
  const std::string sweep = "sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.8]\n";
  const std::string h = Expand(sweep).hash;
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(Expand(sweep, {"sweep.replicates=5"}).hash, h);
  EXPECT_NE(Expand(sweep, {"scenario.duration=90"}).hash, h);
  EXPECT_NE(Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.9]\n").hash, h);
}

Json Metrics(long encounters, long collisions) {
  Json m;
  for (const std::string& c : MetricColumns()) {
    const Metric* metric = FindMetric(c);  // NAME_lo / NAME_hi: a rate's interval
    m[c] = metric && metric->type != MetricType::kReal ? Json(1) : Json(0.5);
  }
  m["encounters"] = encounters;
  m["collisions"] = collisions;
  m["dc"] = 0;
  return m;
}

TEST(SweepJournal, TornTailIgnoredOtherSweepRefusedOkWins) {
  const Plan p = Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.8]\n");
  const Json ok = JournalEntry(p, p.tasks[1], "ok", "",
                               {{"no_trust", Metrics(10, 2)}, {"ta_ebp", Metrics(0, 0)}});
  const Json failed = JournalEntry(p, p.tasks[1], "failed", "boom", nullptr);
  const std::string text = failed.dump() + "\n" + ok.dump() + "\n" + failed.dump() + "\n" +
                           "{\"hash\":\"" + p.hash + "\",\"poi";
  const Journal j = ParseJournal(text, p, "journal.jsonl");
  EXPECT_TRUE(j.partial_tail);
  EXPECT_EQ(j.valid_bytes, text.rfind('\n') + 1);
  EXPECT_EQ(j.lines, 3u);
  ASSERT_EQ(j.entries.size(), 1u);
  EXPECT_EQ(j.entries.at(1).value("status", ""), "ok");

  const Plan other = Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.3]\n");
  try {
    ParseJournal(ok.dump() + "\n", other, "dir/journal.jsonl");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("dir/journal.jsonl:1: the journal belongs to a different sweep"));
  }

  // Tables: rates of a run without encounters are empty; a failed task has a
  // row per policy with its error.
  Journal both = j;
  AddEntry(&both, p, JournalEntry(p, p.tasks[2], "failed", "config error: model.trust", nullptr));
  const std::string csv = ResultsCsv(p, both);
  EXPECT_THAT(csv, HasSubstr("\n0,1,11,0.2,no_trust,ok,,,10,2,0.5,"));
  EXPECT_THAT(csv, HasSubstr("\n0,1,11,0.2,ta_ebp,ok,,,0,0,,,,,,1,0,,,,,,0.5,0.5,0.5,0.5,,,1,"));
  EXPECT_THAT(csv, HasSubstr("\n1,0,10,0.8,ta_ebp,failed,config error: model.trust,,,"));
  EXPECT_THAT(ResultsJsonl(p, both), HasSubstr("\"collision_rate\":null"));
  const std::string agg = AggregateCsv(p, both);
  EXPECT_THAT(agg, HasSubstr("\n0,0.2,no_trust,1,0,10,2,0.2,"));
  EXPECT_THAT(agg, HasSubstr("\n1,0.8,ta_ebp,0,1,,"));
}

// Lines that parse as JSON but are not entries of the right shape are named
// (origin:line) and skipped, never thrown as a JSON type error nor summed
// into the tables (counts that are negative, fractional or beyond 2^53).
TEST(SweepJournal, LinesOfTheWrongShapeAreNamedAndSkipped) {
  const Plan p = Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.8]\n");
  const std::string h = "\"hash\":\"" + p.hash + "\"";
  const std::vector<std::string> bad = {
      "not json",
      "[1, 2]",
      "{\"point\":0,\"replicate\":0,\"status\":\"ok\"}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":7}",
      "{" + h + ",\"point\":\"0\",\"replicate\":0,\"status\":\"ok\",\"policies\":{}}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"policies\":[]}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"policies\":{\"ta_ebp\":{\"encounters\":-1}}}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"policies\":{\"ta_ebp\":{\"encounters\":1.5}}}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"policies\":{\"ta_ebp\":{\"dc\":1e300}}}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"policies\":{\"ta_ebp\":{\"wait_mean\":\"abc\"}}}",
      "{" + h + ",\"point\":0,\"replicate\":0,\"status\":\"ok\",\"error\":3,\"policies\":{}}",
  };
  std::string text;
  for (const std::string& line : bad) text += line + "\n";
  Journal j;
  ASSERT_NO_THROW(j = ParseJournal(text, p, "dir/journal.jsonl"));
  EXPECT_TRUE(j.entries.empty());
  EXPECT_EQ(j.lines, 0u);
  ASSERT_EQ(j.corrupt.size(), bad.size());
  for (std::size_t i = 0; i < bad.size(); ++i)
    EXPECT_THAT(j.corrupt[i], HasSubstr("dir/journal.jsonl:" + std::to_string(i + 1) + ": "));
  EXPECT_THAT(j.corrupt[3], HasSubstr("\"status\""));
  EXPECT_THAT(j.corrupt[6], HasSubstr("policies.ta_ebp.encounters"));
  EXPECT_NO_THROW(ResultsCsv(p, j));
  EXPECT_NO_THROW(AggregateCsv(p, j));
}

// AddEntry says whether it stored the entry (merge takes a task's outputs
// from the shard whose entry is kept); CountTasks tallies ok/failed/missing.
TEST(SweepJournal, AddEntryReportsWhatItKeptAndCountTasksTallies) {
  const Plan p = Expand("sweep:\n  replicates: 2\n  grid:\n    model.trust: [0.2, 0.8]\n");
  const Json ok = JournalEntry(p, p.tasks[1], "ok", "", {{"no_trust", Metrics(10, 2)}});
  const Json failed = JournalEntry(p, p.tasks[1], "failed", "boom", nullptr);
  Journal j;
  EXPECT_TRUE(AddEntry(&j, p, failed));   // first entry
  EXPECT_TRUE(AddEntry(&j, p, ok));       // ok replaces failed
  EXPECT_FALSE(AddEntry(&j, p, failed));  // failed never replaces ok
  EXPECT_TRUE(IsOk(j.entries.at(1)));
  EXPECT_TRUE(AddEntry(&j, p, ok));       // a later ok is the one kept
  Json outside = ok;
  outside["replicate"] = 5;
  EXPECT_FALSE(AddEntry(&j, p, outside));
  EXPECT_TRUE(AddEntry(&j, p, JournalEntry(p, p.tasks[2], "failed", "boom", nullptr)));
  const Tally t = CountTasks(p.tasks, j);
  EXPECT_EQ(t.ok, 1);
  EXPECT_EQ(t.failed, 1);
  EXPECT_EQ(t.missing, 2);
}

}  // namespace
}  // namespace taebp::sweep
