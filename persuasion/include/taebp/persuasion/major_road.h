// The major-road encounter (issue 16, item 2): the AV waits at the MINOR road's
// stop line, an HV approaches on a conflicting MAJOR movement (it has the right
// of way and does not stop). The AV (intent Go with prior lambda, or Stop)
// commits to a scheme and nudges to signal; the HV yields (DC: slows down so the
// AV can go first) or keeps its way at speed (DR). See docs/beyond/major-road.md.
//
// The HV's utility (rows Go, Stop; columns DR, DC), c >= 0 the cost of the
// yielding manoeuvre itself (braking from speed and getting back to it):
//   u: DR -> (-r, 1),  DC -> (-c, -1 - c);   v (the AV's): DR -> -1, DC -> +1.
// c = 0 is the paper's table. It is the paper's game with the effective penalty
//   r_eff = 2 (r - c) / (2 + c)
// (u_major = k u_paper(r_eff) + h(w) with k = (2 + c)/2 > 0, h = (-c, -c/2), so
// every best response, threshold and design is the same), hence
//   p* = (2 + c)/(2 + r),  theta* = (p* - lambda)/(1 - lambda)  (unbounded L).
// Every function below is the paper's function evaluated at
// EquivalentPaperParams(); none re-derives the math.
//
// ClassifyMajorRoadApproach says whether a given approach is this game at all
// (pure kinematics: the HV close enough that both proceeding collides, far
// enough that it can still yield comfortably).
//
// Pure math: no SUMO, no config.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"
#include "taebp/persuasion/tolerance.h"

#include <optional>
#include <string>

namespace taebp::persuasion {

struct MajorRoadParams {
  double prior_go = 0.2;           // lambda = p0(Go), in (0, 1)
  double collision_penalty = 3.0;  // r > 0: the HV's utility -r for DR when the AV goes
  double yield_cost = 0.0;         // c in [0, r): the cost of yielding, paid whatever the AV does
  // False (message naming the field and value) for lambda outside (0, 1), r not
  // > 0 and finite, c negative, not finite or c >= r (then keeping its way is
  // weakly dominant for the HV: no signal can make it yield).
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument with the IsValid message
  // The strategically equivalent paper game {lambda, r_eff}.
  AvHvParams EquivalentPaperParams() const;
};

// The HV's table as a Game (states {Go, Stop}, actions {DR, DC}, the paper's
// sender utility), for the general theorems (BestResponse, MinPersuadableTrust,
// IndifferencePosterior).
Game MajorRoadGame(const MajorRoadParams& params);

// r_eff = 2 (r - c) / (2 + c), in (0, r]; r_eff = r iff c = 0.
double MajorRoadEffectivePenalty(const MajorRoadParams& params);

// eq:ppp for the major-road table: p* = (2 + c) / (2 + r).
double MajorRoadPStar(const MajorRoadParams& params);

// eq:tt analogue: theta* = (2(1 - lambda) + c - r lambda) / ((1 - lambda)(2 + r)),
// clamped to [0, 1]; 0 when lambda >= p* (the HV yields at the prior).
double MajorRoadThetaStar(const MajorRoadParams& params);

// True if the HV yields (DC) at belief p_go in Go: p_go >= p*, ties toward the
// AV; HvDrivesIfClear of the equivalent paper game (its tie band).
bool MajorRoadHvYields(const MajorRoadParams& params, double p_go);

// Theorem 2 / eq:b / Section IV-C for the major road: DesignTaebp of the
// equivalent paper game (theta_star is the likelihood model's, p_star = (2+c)/(2+r)).
TaebpDesign DesignMajorRoad(const MajorRoadParams& params, double theta_hat,
                            const LikelihoodModel& model);

// What the AV commits to, and the predicted per-encounter rates (DC = the HV
// yields, collision = the AV goes and the HV keeps its way), for the policies
// of outcomes.h: CommitScheme / PredictOutcome of the equivalent paper game.
CommittedScheme CommitMajorRoadScheme(Policy policy, const MajorRoadParams& params,
                                      double theta_hat, const LikelihoodModel& model);
PredictedOutcome PredictMajorRoadOutcome(Policy policy, const MajorRoadParams& params,
                                         double theta_true, const LikelihoodModel& model,
                                         std::optional<double> theta_hat = std::nullopt);

// ---------------------------------------------------------------------------
// When is an approach the game at all (docs/beyond/major-road.md, "When is it a game").
// Times run from the decision instant t = 0: the HV has the AV's signal in view
// and the AV, if it goes, starts then. Distances along the HV's path, metres;
// speeds m/s; seconds.
struct MajorRoadApproach {
  double hv_distance = 30.0;              // d >= 0: the HV's front to the conflict zone's entry
  double hv_speed = 13.89;                // v > 0: the HV's current speed (kept under DR)
  double comfortable_deceleration = 3.0;  // a > 0: the braking the HV accepts to yield
  double reaction_time = 0.0;             // t_r >= 0: from t = 0 until the HV starts braking
  double hv_occupancy_length = 8.0;       // l >= 0: the conflict zone's length along the HV's
                                          //   path plus the HV's length
  double av_enter_time = 1.0;             // t_in >= 0: when the AV, going at t = 0, enters the zone
  double av_clear_time = 3.0;             // t_out > t_in: when it has left it (its crossing time)
  bool IsValid(std::string* why) const;   // message names the field and value
  void Validate() const;
};

enum class ApproachKind {
  kHvPassesFirst,  // d + l <= v t_in: at its speed the HV clears the zone before the AV enters
  kAvClearsFirst,  // d >= v t_out: the AV clears the zone before the HV arrives
  kCannotYield,    // they would collide, but the HV cannot yield comfortably (d < yield distance)
  kGame,           // they would collide, and the HV can yield: the persuasion game
};
const char* ToString(ApproachKind kind);

struct ApproachWindow {
  ApproachKind kind = ApproachKind::kAvClearsFirst;
  double time_to_arrival = 0.0;        // d / v
  double conflict_min_distance = 0.0;  // v t_in - l: collide iff d in (this, conflict_max)
  double conflict_max_distance = 0.0;  // v t_out
  double yield_distance = 0.0;         // distance the HV covers by t_out when it reacts at t_r
                                       //   and then brakes at a (stopping if it reaches 0);
                                       //   it can yield iff d >= this
  double stopping_distance = 0.0;      // v t_r + v^2 / (2a) (>= yield_distance)
  bool IsGame() const { return kind == ApproachKind::kGame; }
};
// The game window: yield_distance <= d < v t_out and d > v t_in - l. Non-empty
// iff t_out > t_r (a > 0): an HV that cannot start braking before the AV has
// crossed can never yield in time.
ApproachWindow ClassifyMajorRoadApproach(const MajorRoadApproach& approach);

}  // namespace taebp::persuasion
