// HVs who learn what a signal meant (model.experience, issue 29) on the
// figure-8 in SUMO, through the runner as `taebp run configs/influence.yaml`
// does it: every HV decision replayed from the records alone (the displacement
// SUMO reported and whether the AV then went, per HV in encounter order)
// through the library's learning rule; always_nudge unlearned within the
// hour; guarded ta_ebp never colliding, its DC rate inside the 99.9 % Wilson
// interval of the mean-field path; the paper's scheme on the knife edge.
#include "taebp/report/clustered.h"
#include "taebp/config/config.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/experience.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/report/report.h"
#include "taebp/runner/runner.h"
#include "clustered_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace taebp {
namespace {

namespace per = persuasion;
const std::string kInfluence = std::string(TAEBP_SOURCE_DIR) + "/configs/influence.yaml";

struct Tally {
  long n = 0, dc = 0, collisions = 0, dr_after_nudge = 0, nudges = 0;
  double theory_dc = 0, theory_collisions = 0;
};

// Replays each HV's encounters through SignalExperience / ExperiencedBelief
// from what the records say SUMO showed it; every decision must match.
Tally Replay(const PolicyRun& run, double forgetting = 1.0) {
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  std::map<std::string, per::SignalExperience> seen;
  Tally t;
  std::vector<EncounterRecord> recs = run.encounters;
  std::stable_sort(recs.begin(), recs.end(),
                   [](const EncounterRecord& a, const EncounterRecord& b) { return a.decided_at < b.decided_at; });
  for (const EncounterRecord& e : recs) {
    per::SignalExperience& x = seen.try_emplace(e.hv, 0.1, forgetting).first->second;
    const double reading = std::clamp(e.observed, 0.0, 2.0);
    const double belief = per::ExperiencedBelief(run.scheme.Signals() ? run.scheme : per::CommittedScheme{},
                                                 params, 0.6, model, reading, x.At(reading), 20.0);
    EXPECT_NEAR(e.posterior, belief, 1e-12) << run.policy << " " << e.hv << " at " << e.time;
    EXPECT_EQ(e.hv_dc, per::HvDrivesIfClear(params, belief)) << run.policy << " " << e.hv;
    x.Record(reading, e.av_first);
    ++t.n;
    t.dc += e.hv_dc;
    t.collisions += e.collision;
    t.nudges += e.commanded > 0;
    t.dr_after_nudge += e.commanded > 0 && !e.hv_dc;
    t.theory_dc += e.theory_dc;
    t.theory_collisions += e.theory_collision;
  }
  return t;
}

// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(ExperienceInSumo, HvsLearnFromSumosDisplacementAlwaysNudgeIsUnlearnedGuardedTaebpNeverCollides) {
  const ExperimentResult r =
      RunExperiment(kInfluence, {"scenario.duration=3600", "scenario.seed=3",
                                 "policies=[always_nudge, ta_ebp]"});
  ASSERT_EQ(r.runs.size(), 2u);
  const Tally nudge = Replay(r.runs[0]);
  const Tally ta = Replay(r.runs[1]);
  ASSERT_GT(nudge.n, 300);
  ASSERT_GT(ta.n, 300);
  // always_nudge: every HV's first encounter is DC (the tie), then the nudge
  // is learned as meaning the prior: few DC, collisions near lambda.
  EXPECT_LT(static_cast<double>(nudge.dc) / nudge.n, 0.1);
  EXPECT_GE(nudge.dc, 8);
  EXPECT_TRUE(test::InsideRun999(r.runs[0], "collision_rate", nudge.theory_collisions / nudge.n));
  EXPECT_TRUE(test::InsideRun999(r.runs[0], "dc_rate", nudge.theory_dc / nudge.n));
  // Guarded ta_ebp: no nudge is ever read as DR, no collision.
  EXPECT_EQ(ta.dr_after_nudge, 0);
  EXPECT_EQ(ta.collisions, 0);
  EXPECT_EQ(ta.theory_collisions, 0.0);
  EXPECT_TRUE(test::InsideRun999(r.runs[1], "dc_rate", ta.theory_dc / ta.n))
      << ta.dc << "/" << ta.n << " vs " << ta.theory_dc / ta.n;
  EXPECT_GT(static_cast<double>(ta.dc) / ta.n, 0.25);
  EXPECT_NEAR(r.runs[1].beyond.long_run_dc, 0.375, 1e-12);
  EXPECT_NEAR(r.runs[0].beyond.long_run_collision, 0.2, 1e-12);
}

TEST(ExperienceInSumo, ThePapersSchemeAgainstALearnerSitsOnTheKnifeEdge) {
  const ExperimentResult r =
      RunExperiment(kInfluence, {"scenario.duration=3600", "scenario.seed=3", "policies=[ta_ebp]",
                                 "model.experience.design=paper"});
  const Tally t = Replay(r.runs[0]);
  ASSERT_GT(t.n, 300);
  EXPECT_GT(t.dr_after_nudge, t.nudges / 5);  // about half in the long run
  EXPECT_GT(t.collisions, 0);
  EXPECT_TRUE(test::InsideRun999(r.runs[0], "collision_rate", t.theory_collisions / t.n));
  EXPECT_TRUE(test::InsideRun999(r.runs[0], "dc_rate", t.theory_dc / t.n));
  EXPECT_NEAR(r.runs[0].beyond.long_run_collision, 0.1, 1e-12);
}

// Issue 42's acceptance on a shorter run (the mean field has reached its
// stationary state within the hour: 1 / (1 - rho) = 20 encounters of an HV's
// about 50): HVs who forget (rho = 0.95), the robust design, which is not
// told the rule. Every decision replayed with the forgetting learner; TA-EBP
// collides at most 0.01 per encounter and keeps DC at least 0.05 above full
// revelation's. The 8-hour figures are on docs/influence.md.
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(ExperienceInSumo, TheRobustDesignAgainstAForgettingLearnerIsSafeAndBeatsFullReveal) {
  const ExperimentResult r = RunExperiment(
      kInfluence, {"scenario.duration=3600", "scenario.seed=3", "model.experience.forgetting=0.95",
                   "model.experience.design=robust", "policies=[ta_ebp, full_reveal]"});
  ASSERT_EQ(r.runs.size(), 2u);
  const Tally ta = Replay(r.runs[0], 0.95);
  const Tally reveal = Replay(r.runs[1], 0.95);
  ASSERT_GT(ta.n, 300);
  ASSERT_GT(reveal.n, 300);
  // The robust scheme: s_max, a = 1, b = 0.2 * 0.3 / (0.7 * 0.8) (margin 0.1).
  EXPECT_EQ(r.runs[0].scheme.nudge, 2.0);
  EXPECT_NEAR(r.runs[0].scheme.b, 0.2 * 0.3 / (0.7 * 0.8), 1e-12);
  const double ta_dc = static_cast<double>(ta.dc) / ta.n;
  const double reveal_dc = static_cast<double>(reveal.dc) / reveal.n;
  EXPECT_LE(static_cast<double>(ta.collisions) / ta.n, 0.01);
  EXPECT_GE(ta_dc, reveal_dc + 0.05) << ta_dc << " vs " << reveal_dc;
  EXPECT_TRUE(test::InsideRun999(r.runs[0], "dc_rate", ta.theory_dc / ta.n))
      << ta.dc << "/" << ta.n << " vs " << ta.theory_dc / ta.n;
  EXPECT_NEAR(r.runs[0].beyond.long_run_dc, 0.2 / 0.7, 1e-6);
  EXPECT_LT(r.runs[0].beyond.long_run_collision, 1e-6);
}

// HVs of different prior strengths (model.experience.strengths: k = 2 or
// 200, by a hash of each HV's id): each HV's theory is the path for its own
// k; the guarded design, which assumes k = 20, still never collides (at s*
// its test is free of k: persuasion.ExperiencePath.GuardedForOneK...).
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(ExperienceInSumo, HvsOfDifferentStrengthsFollowTheirOwnPaths) {
  const ExperimentResult r = RunExperiment(
      kInfluence, {"scenario.duration=3600", "scenario.seed=3", "model.experience.strengths=[2, 200]",
                   "policies=[always_nudge, random_nudge, ta_ebp]"});
  ASSERT_EQ(r.runs.size(), 3u);
  for (const PolicyRun& run : r.runs) {
    double dc = 0, coll = 0;
    for (const EncounterRecord& e : run.encounters) {
      dc += e.theory_dc;
      coll += e.theory_collision;
    }
    const double n = static_cast<double>(run.encounters.size());
    ASSERT_GT(n, 300) << run.policy;
    EXPECT_TRUE(test::InsideRun999(run, "dc_rate", dc / n)) << run.policy << " theory " << dc / n;
    EXPECT_TRUE(test::InsideRun999(run, "collision_rate", coll / n)) << run.policy << " theory " << coll / n;
  }
  long collisions = 0;
  for (const EncounterRecord& e : r.runs[2].encounters) collisions += e.collision;
  EXPECT_EQ(collisions, 0);
}

// HVs who read the displacement with noise (model.noise with
// model.experience, issue 42's noisy learner): each HV files a reading under
// the level it perceived (hv_reading), every decision replayed from those
// readings; the runs have no theory (the level is random); the robust design,
// whose nudge s_max reads above s* even with the noise, still never collides,
// and the noise reaches the learner (most readings differ from SUMO's).
// taebp-test: study (the plain half only, once; tests/CMakeLists.txt)
TEST(ExperienceInSumo, NoisyLearnersFileWhatTheyPerceivedAndTheRobustDesignHolds) {
  const ExperimentResult r = RunExperiment(
      kInfluence, {"scenario.duration=3600", "scenario.seed=3",
                   "model.noise={kind: gaussian, scale: 0.1, design: paper}",
                   "model.experience.design=robust", "policies=[ta_ebp, always_nudge]"});
  ASSERT_EQ(r.runs.size(), 2u);
  const per::LinearLikelihood model(2.0);
  const per::AvHvParams params{0.2, 3.0};
  for (const PolicyRun& run : r.runs) {
    std::map<std::string, per::SignalExperience> seen;
    std::vector<EncounterRecord> recs = run.encounters;
    std::stable_sort(recs.begin(), recs.end(), [](const EncounterRecord& a, const EncounterRecord& b) {
      return a.decided_at < b.decided_at;
    });
    long noisy = 0, collisions = 0;
    for (const EncounterRecord& e : recs) {
      per::SignalExperience& x = seen.try_emplace(e.hv, 0.1).first->second;
      const double reading = e.beyond.reading;
      ASSERT_GE(reading, 0.0);
      ASSERT_LE(reading, 2.0);
      noisy += std::abs(reading - std::clamp(e.observed, 0.0, 2.0)) > 1e-9;
      const double belief = per::ExperiencedBelief(run.scheme, params, 0.6, model, reading, x.At(reading), 20.0);
      EXPECT_NEAR(e.posterior, belief, 1e-12) << run.policy << " " << e.hv << " at " << e.time;
      EXPECT_EQ(e.hv_dc, per::HvDrivesIfClear(params, belief)) << run.policy << " " << e.hv;
      EXPECT_TRUE(std::isnan(e.theory_dc)) << run.policy;
      x.Record(reading, e.av_first);
      collisions += e.collision;
    }
    ASSERT_GT(recs.size(), 300u) << run.policy;
    // About half: a reading clamped at 0 or s_max equals what SUMO showed.
    EXPECT_GT(noisy, static_cast<long>(recs.size()) / 4) << run.policy;
    if (run.policy == "ta_ebp") EXPECT_EQ(collisions, 0);
    else EXPECT_GT(collisions, static_cast<long>(recs.size()) / 10);  // always_nudge: learned
  }
}

}  // namespace
}  // namespace taebp
