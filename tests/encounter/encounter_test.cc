// The SUMO-free pieces of an encounter: the AV's draws, the HV's reading of a
// nudge, the release sequence and the creep profile of a nudge. (Right of way
// at a junction: interception_test.cc.)
#include "taebp/encounter/encounter.h"

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

namespace taebp {
namespace {

namespace per = persuasion;
// ------------------------------------------------------------------ randomness

TEST(Uniform01, InUnitIntervalAndPortable) {
  std::mt19937_64 rng(12345);
  double lo = 1, hi = 0, sum = 0;
  const int n = 1000000;
  for (int i = 0; i < n; ++i) {
    const double u = Uniform01(rng);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
  }
  // Mean within 5 standard errors of 1/2 (sd of U(0,1) is 1/sqrt(12)).
  EXPECT_NEAR(sum / n, 0.5, 5.0 / std::sqrt(12.0 * n));
  EXPECT_LT(lo, 1e-4);
  EXPECT_GT(hi, 1 - 1e-4);
  // Portable: the standard fixes mt19937_64's 10000th output for the default
  // seed (9981545732273789042); Uniform01 is its top 53 bits over 2^53.
  std::mt19937_64 std_rng;
  std_rng.discard(9999);
  EXPECT_EQ(Uniform01(std_rng), static_cast<double>(9981545732273789042ull >> 11) * 0x1.0p-53);
  // The largest output maps below 1.
  EXPECT_LT(static_cast<double>(std::numeric_limits<std::uint64_t>::max() >> 11) * 0x1.0p-53, 1.0);
}

// Binomial check: |k/n - p| <= 5 standard errors (false-failure rate ~6e-7).
void ExpectRate(long k, long n, double p, const char* what) {
  ASSERT_GT(n, 0) << what;
  const double se = std::sqrt(p * (1 - p) / n);
  const double rate = static_cast<double>(k) / n;
  if (p == 0.0 || p == 1.0) {
    EXPECT_EQ(rate, p) << what;
  } else {
    EXPECT_NEAR(rate, p, 5 * se) << what << ": " << k << " of " << n;
  }
}

TEST(DrawAv, FrequenciesMatchLambdaAB) {
  struct Case {
    double lambda;
    per::CommittedScheme scheme;
  };
  const std::vector<Case> cases = {
      {0.2, {true, 1.641025641025641, 1.0, 0.21875}},  // the paper's TA-EBP
      {0.3, {true, 0.8, 0.7, 0.05}},
      {0.1, {false, 0.0, 0.0, 0.0}},  // no_ebp: never nudges, never goes
      {0.5, {true, 2.0, 1.0, 0.0}},   // full reveal
  };
  const long n = 200000;
  for (const Case& c : cases) {
    std::mt19937_64 rng(7);
    long go = 0, nudge_go = 0, nudge_stop = 0, first = 0;
    for (long i = 0; i < n; ++i) {
      const AvDraw d = DrawAv(c.scheme, c.lambda, rng);
      go += d.intent_go;
      if (d.intent_go) nudge_go += d.nudge;
      else nudge_stop += d.nudge;
      first += d.goes_first;
      ASSERT_EQ(d.goes_first, d.intent_go && c.scheme.av_may_go);
      ASSERT_EQ(d.nudge_distance, d.nudge ? c.scheme.nudge : 0.0);
      if (c.scheme.nudge == 0.0) {
        ASSERT_FALSE(d.nudge);
      }
    }
    ExpectRate(go, n, c.lambda, "P(Go)");
    ExpectRate(nudge_go, go, c.scheme.nudge > 0 ? c.scheme.a : 0.0, "P(nudge | Go)");
    ExpectRate(nudge_stop, n - go, c.scheme.nudge > 0 ? c.scheme.b : 0.0, "P(nudge | Stop)");
    ExpectRate(first, n, c.scheme.av_may_go ? c.lambda : 0.0, "P(AV goes first)");
  }
}

TEST(DrawAv, AlwaysConsumesTwoUniformsSoSchemesShareStreams) {
  const std::vector<per::CommittedScheme> schemes = {
      {true, 1.641025641025641, 1.0, 0.21875},
      {true, 1.4545454545454546, 1.0, 0.25},
      {false, 0.0, 0.0, 0.0},
      {true, 2.0, 1.0, 0.0},
      {true, 2.0, 1.0, 1.0, /*random_magnitude=*/true}};  // random_nudge: its magnitude elsewhere
  // Each draw advances the engine by exactly two outputs.
  for (const per::CommittedScheme& s : schemes) {
    std::mt19937_64 rng(99), reference(99);
    for (int i = 0; i < 1000; ++i) {
      const double u_intent = Uniform01(reference);
      const double u_signal = Uniform01(reference);
      const AvDraw d = DrawAv(s, 0.2, rng);
      ASSERT_EQ(rng, reference) << i;
      ASSERT_EQ(d.intent_go, u_intent < 0.2);
      ASSERT_EQ(d.nudge, s.nudge > 0 && u_signal < (d.intent_go ? s.a : s.b));
    }
  }
  // Two policies fed from the same seed see the same intents, encounter by encounter.
  std::mt19937_64 r1(2024), r2(2024);
  for (int i = 0; i < 10000; ++i) {
    const AvDraw d1 = DrawAv(schemes[0], 0.3, r1);
    const AvDraw d2 = DrawAv(schemes[2], 0.3, r2);
    ASSERT_EQ(d1.intent_go, d2.intent_go) << i;
  }
}

// ------------------------------------------------------------------ HV reading

TEST(ReadNudge, IsThePosteriorOfTheLibraryClampedToTheModelRange) {
  const per::LinearLikelihood linear(2.0);
  const per::LogisticLikelihood logistic(2.0, 4.0, 1.0);
  const per::CommittedScheme reveal{true, 2.0, 1.0, 0.0};  // a signalling scheme
  for (const per::LikelihoodModel* model :
       std::vector<const per::LikelihoodModel*>{&linear, &logistic}) {
    for (const per::AvHvParams params : {per::AvHvParams{0.2, 3.0}, per::AvHvParams{0.3, 2.0}}) {
      for (double theta : {0.0, 0.25, 0.6, 1.0}) {
        for (double s : {0.0, 0.5, 1.4545454545454546, 1.641025641025641, 1.9999, 2.0}) {
          const HvReading r = ReadNudge(reveal, params, theta, *model, s);
          EXPECT_EQ(r.observed, s);
          EXPECT_EQ(r.posterior, per::HvPosteriorGo(params, theta, *model, s));
          EXPECT_EQ(r.drives_if_clear, per::HvDrivesIfClear(params, r.posterior));
        }
        // Past s_max (SUMO overshoot, the full-reveal nudge + kNudgeOvershoot)
        // reads as s_max; a round-off negative displacement reads as 0.
        for (double past : {2.0 + 1e-6, 2.001, 3.5}) {
          const HvReading r = ReadNudge(reveal, params, theta, *model, past);
          EXPECT_EQ(r.observed, past);
          EXPECT_EQ(r.posterior, per::HvPosteriorGo(params, theta, *model, 2.0));
        }
        const HvReading neg = ReadNudge(reveal, params, theta, *model, -1e-12);
        EXPECT_EQ(neg.posterior, per::HvPosteriorGo(params, theta, *model, 0.0));
      }
    }
  }
  // The paper's numbers: theta = 0.6 is persuaded by s* = 64/39 but not by
  // No Trust's 16/11 (posterior 0.32 < p* = 0.4).
  const per::AvHvParams paper{0.2, 3.0};
  const per::CommittedScheme taebp = per::CommitScheme(per::Policy::kTaEbp, paper, 0.6, linear);
  EXPECT_TRUE(ReadNudge(taebp, paper, 0.6, linear, 64.0 / 39.0).drives_if_clear);
  const HvReading nt = ReadNudge(taebp, paper, 0.6, linear, 16.0 / 11.0);
  EXPECT_NEAR(nt.posterior, 0.32, 1e-12);
  EXPECT_FALSE(nt.drives_if_clear);
}

// Without a signalling scheme (no_ebp) the AV's standing still tells the HV
// nothing: it keeps its prior and, for lambda = 0.5 > p* = 0.4, drives if clear
// whatever its trust (read as the signal s = 0 it would believe 0.5 (1 - theta)).
TEST(ReadNudge, WithoutASchemeTheHvKeepsItsPrior) {
  const per::LinearLikelihood linear(2.0);
  const per::AvHvParams eager{0.5, 3.0};
  const per::CommittedScheme none = per::CommitScheme(per::Policy::kNoEbp, eager, 0.6, linear);
  ASSERT_FALSE(none.Signals());
  for (double theta : {0.0, 0.6, 1.0}) {
    for (double observed : {0.0, 1e-4, -1e-12}) {
      const HvReading r = ReadNudge(none, eager, theta, linear, observed);
      EXPECT_EQ(r.posterior, 0.5);
      EXPECT_TRUE(r.drives_if_clear);
    }
  }
  const per::CommittedScheme reveal = per::CommitScheme(per::Policy::kFullReveal, eager, 0.6, linear);
  EXPECT_FALSE(ReadNudge(reveal, eager, 0.6, linear, 0.0).drives_if_clear);  // 0.2 < 0.4
}

// ------------------------------------------------------------------ encounter

using Release = EncounterSequence::Release;
bool IsAv(const Release& r) { return r.av && !r.reckless; }
bool IsHv(const Release& r, bool reckless) { return !r.av && r.reckless == reckless; }

TEST(EncounterSequence, AvGoesHvDrivesRecklesslyBothAtOnce) {
  EncounterSequence seq(true, false, 10.0, 1.0);
  const auto out = seq.Update(10.0, false, false);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(std::count_if(out.begin(), out.end(), IsAv), 1);
  EXPECT_EQ(std::count_if(out.begin(), out.end(), [](const Release& r) { return IsHv(r, true); }), 1);
  EXPECT_TRUE(seq.Update(10.1, false, false).empty());
  EXPECT_TRUE(seq.Update(15.0, true, true).empty());
}

TEST(EncounterSequence, AvGoesHvDrivesIfClearOnceTheAvEnteredTheJunction) {
  EncounterSequence seq(true, true, 10.0, 1.0);
  auto out = seq.Update(10.0, false, false);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(IsAv(out[0]));
  // The HV waits until the AV is inside the junction, confirm delay or not.
  for (double t : {10.1, 11.0, 12.0, 30.0}) EXPECT_TRUE(seq.Update(t, false, false).empty()) << t;
  out = seq.Update(30.1, true, false);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(IsHv(out[0], false));
  EXPECT_TRUE(seq.Update(30.2, true, false).empty());
  EXPECT_TRUE(seq.Update(33.0, true, true).empty());
}

TEST(EncounterSequence, AvWaitsHvDrivesRecklesslyAtOnceThenTheAv) {
  EncounterSequence seq(false, false, 10.0, 1.0);
  auto out = seq.Update(10.0, false, false);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(IsHv(out[0], true));
  for (double t : {10.1, 11.0, 20.0}) EXPECT_TRUE(seq.Update(t, false, false).empty()) << t;
  out = seq.Update(20.1, false, true);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(IsAv(out[0]));
  EXPECT_TRUE(seq.Update(20.2, false, true).empty());
}

TEST(EncounterSequence, AvWaitsHvDrivesIfClearAfterConfirmDelayThenTheAv) {
  const double dt = 0.1;
  for (double confirm_delay : {0.0, 1.0, 2.5}) {
    for (int decided_step : {7, 123, 35999}) {
      // Time as the simulation accumulates it, with round-off.
      double now = 0;
      for (int k = 0; k < decided_step; ++k) now += dt;
      const double decided_at = now;
      EncounterSequence seq(false, true, decided_at, confirm_delay);
      const int delay_steps = static_cast<int>(std::lround(confirm_delay / dt));
      int released_at = -1;
      for (int k = 0; k <= delay_steps + 3; ++k) {
        const auto out = seq.Update(now, false, false);
        if (!out.empty()) {
          ASSERT_EQ(out.size(), 1u);
          EXPECT_TRUE(IsHv(out[0], false));
          EXPECT_EQ(released_at, -1) << "released twice";
          released_at = k;
        }
        now += dt;
      }
      // Exactly at decided_at + confirm_delay, not a step late through round-off.
      EXPECT_EQ(released_at, delay_steps) << confirm_delay << " " << decided_step;
      const auto av = seq.Update(now, false, true);
      ASSERT_EQ(av.size(), 1u);
      EXPECT_TRUE(IsAv(av[0]));
      EXPECT_TRUE(seq.Update(now + dt, false, true).empty());
    }
  }
}

// Keep clear: a careful release (the AV, a DC HV) stays due while its exit
// has no room, and happens as soon as it has; a reckless HV ignores it.
TEST(EncounterSequence, CarefulReleasesWaitForRoomRecklessOnesDoNot) {
  {  // AV goes, HV DC: the AV waits for room, then the HV after the AV cleared waits too.
    EncounterSequence seq(true, true, 10.0, 1.0);
    EXPECT_TRUE(seq.Update(10.0, false, false, /*av_may_enter=*/false, true).empty());
    EXPECT_TRUE(seq.Update(12.0, false, false, false, true).empty());
    auto out = seq.Update(12.1, false, false, true, true);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(IsAv(out[0]));
    EXPECT_TRUE(seq.Update(15.0, true, false, true, /*hv_may_enter=*/false).empty());
    out = seq.Update(15.1, true, false, true, true);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(IsHv(out[0], false));
  }
  {  // AV goes, HV DR: the reckless HV goes at once although its exit is full.
    EncounterSequence seq(true, false, 10.0, 1.0);
    const auto out = seq.Update(10.0, false, false, false, false);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(IsHv(out[0], true));
  }
  {  // AV waits, HV DC: the HV after its confirm delay only with room; then the AV only with room.
    EncounterSequence seq(false, true, 10.0, 1.0);
    EXPECT_TRUE(seq.Update(11.0, false, false, true, false).empty());
    auto out = seq.Update(11.5, false, false, true, true);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(IsHv(out[0], false));
    EXPECT_TRUE(seq.Update(14.0, false, true, false, true).empty());
    out = seq.Update(14.1, false, true, true, true);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_TRUE(IsAv(out[0]));
  }
}

// ------------------------------------------------------------------ creep

TEST(CreepSpeed, LandsExactlyWithinLimitsAndNeverOvershoots) {
  const double accel = 2.6, decel = 4.5, creep = 1.0;
  for (double target : {0.3, 1.4545, 1.641, 2.0, 2.0 + 1e-6}) {
    for (double dt : {0.1, 0.05}) {
      SCOPED_TRACE(testing::Message() << "target " << target << " dt " << dt);
      double x = 0, v = 0;
      int steps = 0;
      bool stopped = false;
      while (steps < 10000) {
        const double next = CreepSpeed(target, x, v, dt, accel, decel, creep);
        ASSERT_GE(next, 0.0);
        ASSERT_LE(next, creep + 1e-12);
        ASSERT_LE(next - v, accel * dt + 1e-12) << "step " << steps;
        if (next == 0.0) {
          stopped = true;
          break;
        }
        ASSERT_LE(v - next, decel * dt + 1e-12) << "step " << steps;
        v = next;
        x += v * dt;
        ++steps;
        ASSERT_LE(x, target + 1e-12) << "overshoot at step " << steps;
      }
      ASSERT_TRUE(stopped);
      EXPECT_NEAR(x, target, 1e-12);
      // The final stop from the last creep speed: at most one step of braking
      // beyond decel*dt is allowed, and only then.
      EXPECT_LE(v, decel * dt + 1e-12) << "final stop from " << v;
      // A sensible duration: not slower than creeping at half speed plus ramps.
      EXPECT_LE(steps * dt, target / (0.5 * creep) + creep / accel + creep / decel + 2 * dt);
      // Once there it stays there.
      EXPECT_EQ(CreepSpeed(target, x, 0.0, dt, accel, decel, creep), 0.0);
    }
  }
}

// The same properties over a grid of targets, steps and vehicle limits.
TEST(CreepSpeed, PropertiesHoldOverAGridOfParameters) {
  int cases = 0;
  for (double dt : {0.01, 0.05, 0.1, 0.2, 0.25}) {
    for (double accel : {0.8, 2.6, 5.0}) {
      for (double decel : {1.0, 4.5, 9.0}) {
        for (double creep : {0.3, 1.0, 2.5}) {
          for (int t = 1; t <= 60; ++t) {
            const double target = 0.0137 * t * t;  // 0.0137 .. 49 m, irregular
            double x = 0, v = 0;
            int steps = 0;
            for (; steps < 100000; ++steps) {
              const double next = CreepSpeed(target, x, v, dt, accel, decel, creep);
              if (next == 0.0) break;
              ASSERT_LE(next, creep + 1e-12);
              ASSERT_LE(next - v, accel * dt + 1e-12);
              ASSERT_LE(v - next, decel * dt + 1e-12)
                  << "target " << target << " dt " << dt << " decel " << decel;
              v = next;
              x += v * dt;
              ASSERT_LE(x, target + 1e-12);
            }
            ASSERT_LT(steps, 100000);
            ASSERT_NEAR(x, target, 1e-12) << "target " << target << " dt " << dt;
            // The landing speed is remaining/dt: round-off in x grows with the
            // number of steps and is divided by dt.
            ASSERT_LE(v, decel * dt + 1e-9) << "final stop, target " << target;
            ++cases;
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 5 * 3 * 3 * 3 * 60);
}

TEST(CreepSpeed, ReachesCreepSpeedOnLongNudgesAndZeroTargetIsZero) {
  double x = 0, v = 0, vmax = 0;
  for (int k = 0; k < 1000; ++k) {
    v = CreepSpeed(5.0, x, v, 0.1, 2.6, 4.5, 1.0);
    if (v == 0) break;
    x += v * 0.1;
    vmax = std::max(vmax, v);
  }
  EXPECT_DOUBLE_EQ(vmax, 1.0);
  EXPECT_NEAR(x, 5.0, 1e-12);
  EXPECT_EQ(CreepSpeed(0.0, 0.0, 0.0, 0.1, 2.6, 4.5, 1.0), 0.0);
}

}  // namespace
}  // namespace taebp
