// What every part of persuasion/ shares without linear algebra: the error type,
// the tolerance policy and the answer of Theorem 1 (TrustThreshold). Headers
// that only name a Game (av_hv.h, major_road.h) include this one and not
// persuasion.h, so Eigen is parsed only where a Game's tables are used
// (persuasion.h), not in every file that designs or reads a nudge.
//
// Pure math: no SUMO include may ever appear under persuasion/.
#pragma once

#include <stdexcept>

namespace taebp::persuasion {

// Thrown on bad input. The message names the parameter and the offending value,
// e.g. "trust theta = 1.3 is outside [0, 1]".
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// ---------------------------------------------------------------------------
// The tolerance policy: the one rule behind every comparison in persuasion/.
//
// Every decision the library makes about the receiver is whether she (weakly)
// prefers an action a' to an action a at a belief p, i.e. the sign of the
// expected-utility gain
//     dU(a', a | p) = sum_w p(w) (u(w, a') - u(w, a)).
// That covers eq:receiver_action (BestResponse, DefaultAction), the HV's choice
// at eq:ppp (HvDrivesIfClear: p_go against p*), Theorem 1 (eq:theta_star: an
// action weakly optimal at the prior, an action a fully trusting receiver can
// be brought to), Step 1 of Section IV-C (theta_hat against theta*), eq:s^*
// (does a nudge suffice) and eq:b (is the HV persuadable at all). All of them
// are made by WeaklyPrefers:
//     a' is weakly preferred to a at p  <=>  dU(a', a | p) >= -kTieTolerance * scale,
//     scale = UtilityScale(u) = max_{w,a} u(w, a) - min_{w,a} u(w, a),
// the largest |dU| any belief can produce, so scaling or shifting the utility
// table changes no decision. Weak preference is a tie, and ties go to the sender
// (Section II: "break ties in favor of Sender"); the band of kTieTolerance only
// absorbs round-off in a belief or gain computed to lie exactly on a threshold.
//
// Thresholds (p*, theta*, s*, b) are reported as their exact closed forms, but
// no function decides by comparing theta with theta* or p_go with p*: the
// decision at a threshold is always the receiver's gain evaluated there (for
// Step 1, at the strongest nudge s_max). So two functions cannot disagree near
// a threshold, and at theta* the HV is persuaded by s_max (the Remark after
// Theorem 2).
//
// The LP (lp.h) states obedience as dU >= 0 exactly (ties toward the sender),
// multiplied by P(a), and GLPK satisfies it to its own feasibility tolerance.
// Divided by a tiny P(a) that round-off can become a visible gap in the
// posterior, so the LP's answer is checked the same way as everything else,
// with the looser kObedienceTolerance for solver round-off: a recommendation
// the receiver does not weakly prefer at its own posterior is merged into her
// best response there (which keeps every other recommendation obedient and
// moves the value by at most that recommendation's tiny probability). A
// recommendation whose probability is below kMinSignalProbability counts as
// never sent (NaN posterior). Probability inputs (a prior, a posterior handed
// to HvDrivesIfClear) may miss [0, 1] or a sum of 1 by kProbabilityTolerance.
inline constexpr double kTieTolerance = 1e-9;
inline constexpr double kObedienceTolerance = 1e-6;
inline constexpr double kProbabilityTolerance = 1e-9;
inline constexpr double kMinSignalProbability = 1e-12;

// The policy itself: true when a gain dU(a', a | p) counts as "a' at least as
// good as a" for a utility table of scale `scale` (UtilityScale). `tolerance`
// is relative; only BestResponse's callers ever pass another one.
inline bool WeaklyPrefers(double gain, double scale, double tolerance = kTieTolerance) {
  return gain >= -tolerance * scale;
}

// Theorem 1's answer (eq:theta_star; MinPersuadableTrust in persuasion.h).
struct TrustThreshold {
  double theta_star = 1.0;
  bool persuadable = false;  // some theta in [0,1] persuades to a non-default action
  int default_action = 0;
  int target_action = -1;    // argmin action a' in eq:theta_star, -1 if none
};

// The paper's finite game (persuasion.h); declared here so that a header can
// name it without Eigen.
struct Game;

}  // namespace taebp::persuasion
