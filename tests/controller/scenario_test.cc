// Short SUMO runs of the figure-8 through taebp::RunPolicy: every encounter is
// checked against the library (nudge realised, posterior, HV action, AV action,
// collision), the measured rates against the library's theory (99.9% Wilson
// intervals), determinism, the run's health and bad input.
#include "taebp/config/config.h"
#include "taebp/controller/policy_run.h"
#include "taebp/report/report.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/persuasion.h"
#include "taebp/persuasion/outcomes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "clustered_support.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace taebp {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace per = persuasion;
namespace fs = std::filesystem;

const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";

// The encounters with `hit` against a theory probability p: exact for p = 0
// or 1, else p must lie in the 99.9% interval clustered by HV (the outputs'
// interval, report/clustered.h; Wilson's where the HVs' encounters look
// independent, as with the paper's one trust).
void ExpectAgrees(const std::vector<EncounterRecord>& encounters, const test::EncounterHit& hit,
                  double p, const std::string& what) {
  const long n = static_cast<long>(encounters.size());
  long k = 0;
  for (const EncounterRecord& e : encounters) k += hit(e);
  ASSERT_GT(n, 0) << what;
  if (p == 0.0) {
    EXPECT_EQ(k, 0) << what << ": theory says never";
  } else if (p == 1.0) {
    EXPECT_EQ(k, n) << what << ": theory says always";
  } else {
    const RateInterval ci = test::EncounterRate(encounters, hit, kZ999);
    EXPECT_GE(p, ci.low) << what << ": " << k << "/" << n << " = " << static_cast<double>(k) / n
                         << ", theory " << p;
    EXPECT_LE(p, ci.high) << what << ": " << k << "/" << n << " = "
                          << static_cast<double>(k) / n << ", theory " << p;
  }
}

ExperimentConfig Config(const std::vector<std::string>& overrides) {
  return LoadExperimentConfig(kPaper, overrides);
}

PolicyRun RunOne(const ExperimentConfig& config, const std::string& policy) {
  return RunPolicy(config, policy, BuildScenario(config, ""));
}

// ------------------------------------------------------------------ theory points

struct Point {
  std::string name;
  std::vector<std::string> overrides;
};

std::ostream& operator<<(std::ostream& os, const Point& p) { return os << p.name; }

class ScenarioPoint : public ::testing::TestWithParam<Point> {};

// Simulated time per policy: ~0.14 AV-HV encounters per simulated second, so an
// hour gives ~500 encounters; the 99.9% interval half-width is then <= 0.07.
constexpr double kDuration = 3600;

// One encounter of a run against the library: the nudge commanded (Theorem 2),
// SUMO's displacement realising it, the HV's belief and action at that
// displacement (eq:pp), the AV's move and SUMO's collision exactly when both
// proceed.
void ExpectEncounterFollowsTheLibrary(const EncounterRecord& e, const per::CommittedScheme& scheme,
                                      const per::AvHvParams& params, double theta,
                                      const per::LikelihoodModel& model, double expected_nudge,
                                      const per::PredictedOutcome& theory) {
  const double s_max = model.SMax();
  EXPECT_EQ(e.av.rfind("av", 0), 0u);
  EXPECT_EQ(e.hv.rfind("hv", 0), 0u);
  EXPECT_EQ(e.hv_trust, theta);
  EXPECT_GE(e.decided_at, e.time);
  if (e.commanded > 0) {
    EXPECT_EQ(e.commanded, expected_nudge);
    // SUMO's reported displacement realises the nudge, never short of it.
    EXPECT_GE(e.observed, e.commanded);
    EXPECT_LE(e.observed - e.commanded, kNudgeTolerance);
  } else {
    // A still AV: the HV reads what SUMO reports, which is (nearly) nothing.
    EXPECT_LE(std::abs(e.observed), kNudgeTolerance);
  }
  // The HV's belief and action follow eq:pp at the observed displacement
  // (read as s_max when SUMO's overshoot passes it), or the prior when the
  // scheme never signals (no_ebp, TA-EBP's fallback).
  const double posterior =
      per::HvPosteriorGo(scheme, params, theta, model, std::min(e.observed, s_max));
  EXPECT_NEAR(e.posterior, posterior, 1e-12);
  EXPECT_EQ(e.hv_dc, per::HvDrivesIfClear(params, e.posterior));
  // The AV goes iff its intent is Go and the committed scheme lets it.
  EXPECT_EQ(e.av_first, e.intent_go && scheme.av_may_go);
  // SUMO reports a collision exactly when both proceed.
  EXPECT_EQ(e.collision, e.av_first && !e.hv_dc);
  EXPECT_NEAR(e.theory_dc, theory.dc_rate, 1e-12);
  EXPECT_NEAR(e.theory_collision, theory.collision_rate, 1e-12);
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST_P(ScenarioPoint, EveryEncounterFollowsTheLibraryAndRatesAgreeWithTheory) {
  std::vector<std::string> overrides = GetParam().overrides;
  overrides.push_back("scenario.duration=" + std::to_string(kDuration));
  overrides.push_back("policies=[no_ebp, no_trust, ta_ebp, full_reveal]");
  const ExperimentConfig cfg = Config(overrides);
  ASSERT_TRUE(cfg.model.trust.IsFixed());
  const double theta = cfg.model.trust.value;
  const per::AvHvParams params{cfg.model.prior_go, cfg.model.collision_penalty};
  const auto model = MakeLikelihood(cfg.model.likelihood);
  const double s_max = model->SMax();
  const Scenario files = BuildScenario(cfg, "");

  for (const std::string& name : cfg.policies) {
    SCOPED_TRACE(GetParam().name + " / " + name);
    const per::Policy policy = ParseGamePolicy(name);
    // The AV's design trust, from the config alone.
    const double theta_hat = policy == per::Policy::kNoTrust ? 1.0
                             : cfg.model.assumed_trust     ? *cfg.model.assumed_trust
                                                           : theta;
    const per::CommittedScheme scheme = per::CommitScheme(policy, params, theta_hat, *model);
    const per::PredictedOutcome theory =
        per::PredictOutcome(policy, params, theta, *model, theta_hat);
    // The nudge the AV must command, straight from Theorem 2 (or s_max / none).
    double expected_nudge = 0;
    if (policy == per::Policy::kTaEbp || policy == per::Policy::kNoTrust) {
      const per::TaebpDesign d = per::DesignTaebp(params, theta_hat, *model);
      expected_nudge = d.persuadable ? d.s_star : 0.0;
    } else if (policy == per::Policy::kFullReveal) {
      expected_nudge = s_max;
    }

    const PolicyRun run = RunPolicy(cfg, name, files);
    EXPECT_EQ(run.policy, name);
    EXPECT_NEAR(run.simulated_seconds, kDuration, 1e-6);
    EXPECT_NEAR(run.theory.dc_rate, theory.dc_rate, 1e-12);
    EXPECT_NEAR(run.theory.collision_rate, theory.collision_rate, 1e-12);
    EXPECT_EQ(run.scheme.nudge, scheme.nudge);
    // Health: no teleports, no collision outside an encounter, no deadlock.
    EXPECT_EQ(run.teleports, 0);
    EXPECT_EQ(run.other_collisions, 0);
    EXPECT_LT(run.longest_gap_without_crossing, 60.0);
    EXPECT_GT(run.crossings_av, 0);
    EXPECT_GT(run.crossings_hv, 0);

    const long n = static_cast<long>(run.encounters.size());
    // Enough encounters for the intervals below to mean something.
    ASSERT_GE(n, 200);
    long go = 0, nudges = 0, dc = 0, collisions = 0;
    double last_time = -1;
    for (const EncounterRecord& e : run.encounters) {
      SCOPED_TRACE(testing::Message() << "encounter at t = " << e.time << " " << e.av << "-"
                                      << e.hv);
      EXPECT_GE(e.time, last_time);
      last_time = e.time;
      ExpectEncounterFollowsTheLibrary(e, scheme, params, theta, *model, expected_nudge, theory);
      nudges += e.commanded > 0;
      go += e.intent_go;
      dc += e.hv_dc;
      collisions += e.collision;
    }
    const std::vector<EncounterRecord>& all = run.encounters;
    ExpectAgrees(all, [](const EncounterRecord& e) { return e.intent_go; }, params.prior_go,
                 "P(intent Go)");
    ExpectAgrees(all, [](const EncounterRecord& e) { return e.commanded > 0; }, theory.nudge_rate,
                 "nudge rate");
    ExpectAgrees(all, [](const EncounterRecord& e) { return e.hv_dc; }, theory.dc_rate, "DC rate");
    ExpectAgrees(all, [](const EncounterRecord& e) { return e.collision; }, theory.collision_rate,
                 "collision rate");
    if (policy == per::Policy::kNoEbp) {
      // No information: every HV decides from the prior (DC iff lambda >= p*).
      EXPECT_EQ(nudges, 0);
      EXPECT_EQ(dc, per::HvDrivesIfClear(params, params.prior_go) ? n : 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Theory, ScenarioPoint,
    ::testing::Values(
        // lambda 0.2, r 3, theta 0.6: TA-EBP DC 0.375, No Trust collides at 0.2.
        Point{"Paper", {}},
        Point{"Lambda03R2Theta08",
              {"model.prior_go=0.3", "model.collision_penalty=2", "model.trust=0.8"}},
        Point{"Lambda01R5Theta05",
              {"model.prior_go=0.1", "model.collision_penalty=5", "model.trust=0.5"}},
        // The AV over-estimates trust: its nudge is too small, collisions expected.
        Point{"AssumedTrust09Theta06", {"model.trust=0.6", "model.assumed_trust=0.9"}},
        // Below theta* = 0.25: TA-EBP falls back to always yielding.
        Point{"NotPersuadableTheta01", {"model.trust=0.1"}},
        // lambda = 0.5 > p* = 0.4: No EBP's HVs drive if clear from the prior
        // (a still AV is no signal), the schemes' still AV reads as Stop.
        Point{"LambdaAbovePStar", {"model.prior_go=0.5"}},
        Point{"LogisticLikelihood",
              {"model.likelihood={type: logistic, s_max: 2.0, steepness: 4, midpoint: 1}"}}),
    [](const ::testing::TestParamInfo<Point>& info) { return info.param.name; });

// The theory values the points above are meant to exercise (so a library
// change that silently makes them trivial is noticed).
TEST(ScenarioPoints, CoverCollisionsPersuasionAndFallback) {
  per::LinearLikelihood lik(2.0);
  const per::AvHvParams paper{0.2, 3.0};
  EXPECT_NEAR(per::PredictOutcome(per::Policy::kTaEbp, paper, 0.6, lik).dc_rate, 0.375, 1e-12);
  EXPECT_NEAR(per::PredictOutcome(per::Policy::kNoTrust, paper, 0.6, lik).collision_rate, 0.2,
              1e-12);
  EXPECT_GT(per::PredictOutcome(per::Policy::kTaEbp, paper, 0.6, lik, 0.9).collision_rate, 0.0);
  EXPECT_FALSE(per::DesignTaebp(paper, 0.1, lik).persuadable);
  const per::AvHvParams p2{0.3, 2.0}, p3{0.1, 5.0};
  for (const auto& [params, theta] : {std::pair{p2, 0.8}, std::pair{p3, 0.5}}) {
    const auto o = per::PredictOutcome(per::Policy::kTaEbp, params, theta, lik);
    EXPECT_GT(o.dc_rate, params.prior_go);
    EXPECT_LT(o.dc_rate, 1.0);
    EXPECT_EQ(o.collision_rate, 0.0);
  }
}

// ------------------------------------------------------------------ determinism

Provenance TestProvenance(const ExperimentConfig& cfg) {
  Provenance p;
  p.config_path = kPaper;
  p.config_json = ToJson(cfg);
  p.seed = cfg.scenario.seed;
  p.git_revision = "test";
  p.sumo_version = "test";
  p.taebp_version = "test";
  return p;
}

std::vector<PolicyRun> RunAll(const ExperimentConfig& cfg) {
  const Scenario files = BuildScenario(cfg, "");
  std::vector<PolicyRun> runs;
  for (const std::string& name : cfg.policies) runs.push_back(RunPolicy(cfg, name, files));
  return runs;
}

TEST(ScenarioDeterminism, SameSeedSameOutputsOtherSeedOtherEncounters) {
  const ExperimentConfig cfg = Config({"scenario.duration=600"});
  const Provenance prov = TestProvenance(cfg);
  const std::vector<PolicyRun> a = RunAll(cfg);
  const std::vector<PolicyRun> b = RunAll(cfg);
  ASSERT_EQ(a.size(), 3u);
  for (const PolicyRun& r : a) EXPECT_GT(r.encounters.size(), 20u) << r.policy;
  EXPECT_EQ(SummaryJson(a, prov), SummaryJson(b, prov));
  EXPECT_EQ(EncountersCsv(a), EncountersCsv(b));

  const ExperimentConfig other = Config({"scenario.duration=600", "scenario.seed=2"});
  const std::vector<PolicyRun> c = RunAll(other);
  EXPECT_NE(EncountersCsv(a), EncountersCsv(c));
}

// ------------------------------------------------------------------ bad input

using test::ErrorOf;

using test::TempDir;

// After a failed run libsumo is closed and the next run works.
void ExpectAShortRunStillWorks() {
  const ExperimentConfig cfg = Config({"scenario.duration=60"});
  const PolicyRun run = RunOne(cfg, "ta_ebp");
  EXPECT_GT(run.crossings_av + run.crossings_hv, 0);
  EXPECT_FALSE(Sumo().IsLoaded());
}

TEST(ScenarioBadInput, MissingNetworkIsAConfigErrorNamingTheKey) {
  const ExperimentConfig cfg = Config({"scenario.network=/nonexistent/dir/x.net.xml"});
  const std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(cfg, ""); });
  EXPECT_THAT(msg, HasSubstr("scenario.network"));
  EXPECT_THAT(msg, HasSubstr("/nonexistent/dir/x.net.xml"));
  // Relative paths are resolved against the config's directory.
  const ExperimentConfig rel = Config({"scenario.network=figure8.net.xml"});
  const std::string built = fs::path(DefaultNetworkPath()).parent_path().string();
  EXPECT_EQ(fs::path(BuildScenario(rel, built).net), fs::path(built) / "figure8.net.xml");
  EXPECT_THAT(ErrorOf<ConfigError>([&] { BuildScenario(rel, TAEBP_SOURCE_DIR); }),
              HasSubstr("scenario.network"));
}

// Anything but a regular file as a network or a route file is refused saying
// what it is (a FIFO used to block the run forever, a folder was "no such
// file"), for the figure-8 and for any network.
TEST(ScenarioBadInput, AFolderFifoOrDanglingLinkAsAFileIsRefusedSayingWhatItIs) {
  TempDir dir;
  const fs::path folder = dir.path() / "folder.net.xml";
  fs::create_directories(folder);
  const fs::path fifo = dir.path() / "fifo.net.xml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const fs::path dangling = dir.path() / "dangling.net.xml";
  fs::create_symlink(dir.path() / "gone.net.xml", dangling);
  const std::vector<std::pair<fs::path, std::string>> cases = {
      {folder, "a folder, not a file"},
      {fifo, "a FIFO (named pipe), not a file"},
      {dangling, "a dangling symbolic link"},
      {dir.path() / "missing.net.xml", "no such file"}};
  for (const auto& [path, what] : cases) {
    SCOPED_TRACE(path.string());
    for (const std::string kind : {"figure8", "network"}) {
      std::vector<std::string> set = {"scenario.kind=" + kind, "scenario.network=" + path.string()};
      if (kind == "network") set.push_back("scenario.demand={flow: 100}");
      const ExperimentConfig cfg = Config(set);
      const std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(cfg, ""); });
      EXPECT_THAT(msg, HasSubstr("scenario.network")) << kind;
      EXPECT_THAT(msg, HasSubstr(path.string())) << kind;
      EXPECT_THAT(msg, HasSubstr(what)) << kind;
    }
    const ExperimentConfig routes =
        Config({"scenario.kind=network", "scenario.grid={columns: 2, rows: 2}",
                "scenario.routes=[" + path.string() + "]", "scenario.av_share=0.5"});
    const std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(routes, ""); });
    EXPECT_THAT(msg, HasSubstr("scenario.routes"));
    EXPECT_THAT(msg, HasSubstr(what));
  }
}

// A policy that needs AVs on a demand without any is refused before SUMO
// starts (it used to run with 0 AVs and exit 0): generated demand without
// scenario.av_share, route files whose types scenario.av_types misses.
TEST(ScenarioBadInput, APolicyNeedingAvsWithNoAvInTheDemandIsAConfigError) {
  TempDir dir;
  const std::string routes = dir.Write(
      "cars.rou.xml",
      "<routes>\n  <vType id=\"car\"/>\n  <vType id=\"truck\" length=\"12\"/>\n"
      "  <trip id=\"a\" type=\"car\" depart=\"0\" from=\"left0A0\" to=\"A0left0\"/>\n"
      "</routes>\n");
  auto load = [&](const std::string& scenario, const std::string& policies) {
    const std::string path = dir.Write(
        "c.yaml", "scenario: {kind: network, grid: {columns: 2, rows: 2}, duration: 60, " +
                      scenario + "}\npolicies: [" + policies + "]\n");
    return LoadExperimentConfig(path);
  };
  std::string msg =
      ErrorOf<ConfigError>([&] { BuildScenario(load("demand: {flow: 100}", "no_ebp, ta_ebp"), ""); });
  EXPECT_THAT(msg, HasSubstr("scenario.av_types = [AV] matches no vehicle type of the demand "
                             "(its types: car), so no_ebp, ta_ebp would run with 0 AVs"));
  EXPECT_THAT(msg, HasSubstr("needs scenario.av_share"));
  msg = ErrorOf<ConfigError>(
      [&] { BuildScenario(load("routes: [" + routes + "]", "sumo_native, ta_ebp"), ""); });
  EXPECT_THAT(msg, HasSubstr("(its types: car, truck), so ta_ebp would run with 0 AVs"));
  EXPECT_THAT(msg, HasSubstr("set scenario.av_types"));
  // Fine: AVs drawn (a share of 0 too: a deliberate choice), their type
  // named, or no policy that needs them.
  EXPECT_NO_THROW(BuildScenario(load("demand: {flow: 100}, av_share: 0.3", "ta_ebp"), ""));
  EXPECT_NO_THROW(BuildScenario(load("demand: {flow: 100}, av_share: 0", "ta_ebp"), ""));
  EXPECT_NO_THROW(BuildScenario(load("demand: {flow: 100}", "sumo_native"), ""));
  EXPECT_NO_THROW(
      BuildScenario(load("routes: [" + routes + "], av_types: [truck]", "ta_ebp"), ""));
}

// A selection that takes no junction says what the network has and why each
// junction of a selected type was passed over (it used to say only "selects
// no junction"): a grid built without internal links, and types the network
// does not have.
TEST(ScenarioBadInput, AnEmptySelectionListsTheNetworksTypesAndWhy) {
  TempDir dir;
  const std::string net = (dir.path() / "flat.net.xml").string();
  ASSERT_EQ(std::system(("netgenerate --grid --grid.number 3 --grid.length 100 "
                         "--default-junction-type allway_stop --no-internal-links true -o " +
                         net + " >/dev/null 2>&1")
                            .c_str()),
            0);
  auto load = [&](const std::string& types) {
    const std::string path = dir.Write(
        "c.yaml", "scenario: {kind: network, network: " + net +
                      ", demand: {flow: 100}, av_share: 0.5, junctions: {types: [" + types +
                      "]}}\n");
    return LoadExperimentConfig(path);
  };
  std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(load("allway_stop"), ""); });
  EXPECT_THAT(msg, HasSubstr("scenario.junctions selects no junction in " + net));
  EXPECT_THAT(msg, HasSubstr("The network has 9 allway_stop"));
  EXPECT_THAT(msg, HasSubstr("of the selected types 9 junctions, passed over: "));
  EXPECT_THAT(msg, HasSubstr("without internal lanes (the network was built with "
                             "--no-internal-links"));
  msg = ErrorOf<ConfigError>([&] { BuildScenario(load("priority_stop"), ""); });
  EXPECT_THAT(msg, HasSubstr("The network has 9 allway_stop"));
  EXPECT_THAT(msg, HasSubstr("of the selected types 0 junctions."));
}

TEST(ScenarioBadInput, CorruptNetworkIsAConfigErrorNamingTheFile) {
  TempDir dir;
  const fs::path net = dir.path() / "garbage.net.xml";
  std::ofstream(net) << "this is not a SUMO network <net <<<\n\x01\x02 garbage\n";
  const ExperimentConfig cfg = Config({"scenario.network=" + net.string(),
                                       "scenario.duration=60"});
  const std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(cfg, ""); });
  EXPECT_THAT(msg, HasSubstr("scenario.network"));
  EXPECT_THAT(msg, HasSubstr(net.string()));
  EXPECT_THAT(msg, HasSubstr("not a readable XML file"));
  // XML, but not a SUMO network.
  std::ofstream(net, std::ios::trunc) << "<routes><vehicle id=\"a\"/></routes>\n";
  EXPECT_THAT(ErrorOf<ConfigError>([&] { BuildScenario(cfg, ""); }),
              HasSubstr("not a SUMO network"));
  ExpectAShortRunStillWorks();
}

TEST(ScenarioBadInput, TooManyVehiclesForTheTrackIsAConfigErrorAboutLoopLength) {
  // Without auto_length the track does not grow: refused before SUMO starts.
  const ExperimentConfig fixed =
      Config({"scenario.avs=30", "scenario.hvs=30", "scenario.auto_length=false"});
  const std::string msg = ErrorOf<ConfigError>([&] { BuildScenario(fixed, ""); });
  EXPECT_THAT(msg, HasSubstr("loop_length"));
  EXPECT_THAT(msg, HasSubstr("60 vehicles"));
  // A given network cannot grow: refused when placing the vehicles.
  const ExperimentConfig given = Config({"scenario.avs=30", "scenario.hvs=30",
                                         "scenario.network=" + DefaultNetworkPath()});
  const std::string run_msg = ErrorOf<ConfigError>([&] { BuildScenario(given, ""); });
  EXPECT_THAT(run_msg, HasSubstr("loop_length"));
  EXPECT_THAT(run_msg, HasSubstr("60"));
  EXPECT_FALSE(Sumo().IsLoaded());
  ExpectAShortRunStillWorks();
}

TEST(ScenarioBadInput, StopInsideTheJunctionIsAConfigError) {
  const std::string msg =
      ErrorOf<ConfigError>([&] { Config({"scenario.stop_distance=1.0", "scenario.duration=60"}); });
  EXPECT_THAT(msg, HasSubstr("scenario.stop_distance = 1"));
  EXPECT_THAT(msg, HasSubstr("--set"));
  ExpectAShortRunStillWorks();
}

// ------------------------------------------------------------------ SUMO decides

// Collisions are SUMO's, not a rule's: with the paper's 1.7 m stop an AV that
// nudged and then waits has its nose in the crossing path, and SUMO reports
// the reckless HV hitting it — collisions the rule "the AV goes and the HV
// drives recklessly" does not predict. With the shipped 3.0 m geometry every
// SUMO collision is exactly such a pair (and every such pair collides).
TEST(SumoDecides, CollisionsComeFromSumoNotFromTheRule) {
  const ExperimentConfig tight =
      Config({"scenario.stop_distance=1.7", "scenario.duration=1800", "policies=[no_trust]"});
  const PolicyRun r = RunOne(tight, "no_trust");
  long unpredicted = 0, collisions = 0;
  for (const EncounterRecord& e : r.encounters) {
    collisions += e.collision;
    if (e.collision && !(e.av_first && !e.hv_dc)) {
      ++unpredicted;
      EXPECT_GT(e.commanded, 0.0) << "only a nudged AV intrudes into the crossing path";
      EXPECT_FALSE(e.av_first) << "the AV waited: the rule says no collision";
    }
  }
  EXPECT_GT(unpredicted, 20) << collisions << " collisions in " << r.encounters.size();
  // Shipped geometry: SUMO and the rule agree on every encounter.
  const ExperimentConfig safe = Config({"scenario.duration=1800", "policies=[no_trust]"});
  const PolicyRun s = RunOne(safe, "no_trust");
  long both = 0;
  for (const EncounterRecord& e : s.encounters) {
    EXPECT_EQ(e.collision, e.av_first && !e.hv_dc) << e.av << "/" << e.hv << " at " << e.time;
    both += e.collision;
  }
  EXPECT_GT(both, 20);
}

// The HV reads the displacement SUMO reports, not the commanded distance:
// the creep aims 1e-6 m past the command (kNudgeOvershoot) and SUMO lands
// there to ~1e-15 m, so every reading carries that overshoot; and the run
// itself checked every nudge against its tolerance (none unrealised).
// The tie rule (issue 42): at s* the paper's HV sits exactly on p*; the
// overshoot, not a rounding, puts every reading on the AV's side, strictly
// above p* by more than the tie tolerance (a reading 1e-6 m short is DR).
TEST(SumoDecides, TheHvReadsSumosDisplacementNotTheCommand) {
  const ExperimentConfig cfg = Config({"scenario.duration=900", "policies=[ta_ebp]"});
  const PolicyRun r = RunOne(cfg, "ta_ebp");
  const double p_star = persuasion::AvHvPStar(cfg.model.collision_penalty);
  long nudges = 0;
  for (const EncounterRecord& e : r.encounters) {
    if (e.commanded <= 0) continue;
    ++nudges;
    EXPECT_NEAR(e.observed - e.commanded, kNudgeOvershoot, 1e-9)
        << "the reading is not SUMO's odometer difference";
    EXPECT_GT(e.posterior - p_star, 10 * persuasion::kTieTolerance)
        << "the tie at s* decided by rounding, not by the overshoot";
    EXPECT_TRUE(e.hv_dc);
  }
  const persuasion::LinearLikelihood model(cfg.model.likelihood.s_max);
  const persuasion::AvHvParams params{cfg.model.prior_go, cfg.model.collision_penalty};
  const double s_star = r.scheme.nudge;
  EXPECT_FALSE(persuasion::HvDrivesIfClear(
      params, persuasion::HvPosteriorGo(params, 0.6, model, s_star - kNudgeOvershoot)));
  EXPECT_GT(nudges, 20);
  EXPECT_EQ(r.nudges_unrealised, 0);
}

TEST(NudgeRealised, TheToleranceOfTheRunsCheck) {
  EXPECT_TRUE(NudgeRealised(1.5, 1.5 + 1e-6));
  EXPECT_TRUE(NudgeRealised(1.5, 1.5 + kNudgeTolerance));
  EXPECT_FALSE(NudgeRealised(1.5, 1.5 + 2 * kNudgeTolerance));  // overshot
  EXPECT_FALSE(NudgeRealised(1.5, 1.4));                         // short
  EXPECT_FALSE(NudgeRealised(1.5, 1.5 - 1e-6));
  EXPECT_TRUE(NudgeRealised(0.0, 0.0));  // a still AV stayed still
  EXPECT_TRUE(NudgeRealised(0.0, 0.5 * kNudgeTolerance));
  EXPECT_FALSE(NudgeRealised(0.0, 0.01));  // it moved
}

TEST(ScenarioWarnings, PaperStopDistanceKeepsTheNoseOutOfTheCrossingPath) {
  EXPECT_TRUE(ScenarioWarnings(Config({})).empty());
  const std::vector<std::string> w = ScenarioWarnings(Config({"scenario.stop_distance=1.7"}));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("stop_distance"));
}

}  // namespace
}  // namespace taebp
