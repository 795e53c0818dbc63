// One AV, several HVs: TA-EBP with a public signal (issue 43; the derivation is
// docs/beyond/multi-receiver.md).
//
// Two or three HVs meet the AV at an all-way stop. The nudge is public: every
// HV sees the same one and reads it with its own trust theta_i through eq:pp,
//   p_i = (1 - theta_i) lambda + theta_i q,   q = the common Bayes posterior.
// With a = P(nudge | Go) = 1 and b = P(nudge | Stop), q = lambda / (lambda +
// (1 - lambda) b) > lambda, so p_i grows with theta_i: a scheme that persuades
// an HV persuades every HV that trusts more. The design therefore addresses the
// HVs whose design trust is at least a threshold tau (one of their trusts, at
// least theta*) and is TA-EBP's single-receiver design for tau (DesignTaebp:
// s*(tau), a = 1, b(tau) of eq:b). Each addressed HV drives if clear with
// probability P(tau) = lambda + (1 - lambda) b(tau) = lambda tau / (lambda tau +
// p* - lambda); the others never do. (For lambda >= p* no persuasion is needed
// but the HVs' intuitive reading of a small nudge is "Stop", so a higher trust
// needs a larger nudge: the design is DesignTaebp for the HIGHEST trust, b = 1,
// and every HV drives if clear.)
//
// Objective: the paper's sender utility summed over the HVs of the meeting,
// v = +1 per DC and -1 per DR (Table "utility"), i.e. 2 sum_i P(DC_i) - n =
// 2 k(tau) P(tau) - n with k(tau) HVs addressed. tau is chosen to maximise it;
// ties go to the lower tau (more HVs addressed). Giving up a low-trust HV can
// pay: it raises b for the rest (lambda = 0.2, r = 3, trusts {0.9, 0.6, 0.3}:
// address {0.9, 0.6}). No public scheme does better: the design equals the
// optimum of the general LP (SolvePublicPersuasion, lp_multi.h) on this game.
//
// Safety (the AV's own move, outside the persuasion game): an HV that is not
// addressed drives recklessly whatever the AV shows, so an AV that went on its
// Go intent would collide with it in a lambda share of meetings. The AV goes
// on its Go intent only when every HV of the meeting is addressed
// (scheme.av_may_go); otherwise it yields, the paper's Step 1 fallback applied
// to the meeting, while its nudge still raises the addressed HVs' DC rate.
//
// Pure math: no SUMO, no config. Bad input throws InvalidArgument naming the
// field and value.
#pragma once

#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/outcomes.h"

#include <string>
#include <vector>

namespace taebp::persuasion {

// The meeting as the AV designs for it.
struct MultiReceiverProblem {
  AvHvParams params;                 // lambda and r, shared by every HV
  std::vector<double> design_trusts; // theta_hat_i, one per HV, each in [0, 1]; at least one

  // False with a message naming the field and value, e.g.
  // "design_trusts[2] = 1.3 is outside [0, 1]".
  bool IsValid(std::string* why) const;
  void Validate() const;  // throws InvalidArgument with the IsValid message
};

enum class MultiReceiverStatus {
  kAddressesAll,   // every HV is addressed; the AV goes on its Go intent
  kAddressesSome,  // some HVs are given up (below theta*, or worth less than a larger b)
  kAddressesNone,  // no HV is persuadable: the paper's fallback, no nudge, always yield
};
const char* ToString(MultiReceiverStatus status);

struct MultiReceiverDesign {
  MultiReceiverStatus status = MultiReceiverStatus::kAddressesNone;
  std::string why;                 // one sentence: the threshold chosen and what was given up
  // tau, the design trust DesignTaebp is run for: the lowest addressed one for
  // lambda < p*, the highest (whose nudge is the largest needed) for lambda >= p*;
  // 1 when no HV is persuadable.
  double designed_for = 1.0;
  // Per HV, in input order: it drives if clear after the nudge (at its design trust).
  std::vector<bool> addressed;
  int addressed_count = 0;         // k(tau)
  TaebpDesign design;              // DesignTaebp(params, tau, model); not persuadable when none
  CommittedScheme scheme;          // the public commitment (av_may_go: every HV addressed)
  // Per HV at its design trust, under `scheme` (PredictOutcome).
  std::vector<PredictedOutcome> predicted;
  // The objective at the design trusts: sum_i (2 dc_i - 1), in [-n, n].
  double sender_value = 0.0;
  // The objective of every candidate threshold, in the order of `candidates`
  // (the distinct persuadable design trusts, highest first): for the doc and the tests.
  std::vector<double> candidates;
  std::vector<double> candidate_values;
};

// The design: addresses the HVs at or above the best threshold tau.
MultiReceiverDesign DesignMultiReceiver(const MultiReceiverProblem& problem,
                                        const LikelihoodModel& model);

// What the common scheme does to HVs of true trusts theta_i (each reads the
// public nudge with its own trust; PredictOutcome per HV).
struct MultiReceiverOutcome {
  std::vector<PredictedOutcome> per_receiver;
  double sender_value = 0.0;        // sum_i (2 dc_i - 1)
  double any_collision_rate = 0.0;  // P(the AV goes and at least one HV drives recklessly)
};
// true_trusts: each in [0, 1], at least one ("true_trusts[i] = ..." on error).
MultiReceiverOutcome PredictMultiReceiver(const CommittedScheme& scheme, const AvHvParams& params,
                                          const std::vector<double>& true_trusts,
                                          const LikelihoodModel& model);

}  // namespace taebp::persuasion
