// One AV, several HVs, a public nudge: the threshold design (multi_receiver.h;
// derivation in docs/beyond/multi-receiver.md).
#include "taebp/persuasion/multi_receiver.h"

#include "internal.h"

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace taebp::persuasion {

namespace {

// "name[i] = value is outside [0, 1]" for the first bad entry, "" if none
// (an empty list is bad too).
std::string TrustListProblem(const std::vector<double>& trusts, const char* name) {
  if (trusts.empty()) return std::string(name) + " is empty: the meeting needs at least one HV";
  for (std::size_t i = 0; i < trusts.size(); ++i) {
    if (!(trusts[i] >= 0.0 && trusts[i] <= 1.0)) {
      return std::string(name) + "[" + std::to_string(i) + "] = " + NumberText(trusts[i]) +
             " is outside [0, 1]";
    }
  }
  return "";
}

// TA-EBP's single-receiver design for tau as a commitment (outcomes.cc's
// FromDesign); av_may_go is set by the caller (every HV addressed).
CommittedScheme SchemeOf(const TaebpDesign& design) {
  CommittedScheme scheme;
  if (!design.persuadable) return scheme;
  scheme.nudge = design.s_star;
  scheme.a = design.a;
  scheme.b = design.b;
  return scheme;
}

// The objective sum_i (2 dc_i - 1) of `scheme` for HVs of trusts `trusts`,
// each reading the public nudge with its own trust.
double SenderValue(const std::vector<PredictedOutcome>& outcomes) {
  double value = 0.0;
  for (const PredictedOutcome& o : outcomes) value += 2.0 * o.dc_rate - 1.0;
  return value;
}

std::vector<PredictedOutcome> PerReceiver(const CommittedScheme& scheme, const AvHvParams& params,
                                          const std::vector<double>& trusts,
                                          const LikelihoodModel& model) {
  std::vector<PredictedOutcome> outcomes;
  outcomes.reserve(trusts.size());
  for (double theta : trusts) outcomes.push_back(PredictOutcome(scheme, params, theta, model));
  return outcomes;
}

// True if an HV of trust theta drives if clear after the scheme's nudge.
bool DrivesIfClearAfterNudge(const CommittedScheme& scheme, const AvHvParams& params, double theta,
                             const LikelihoodModel& model) {
  return HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta, model, scheme.nudge));
}

// The candidate thresholds: the distinct design trusts the model's strongest
// nudge persuades (theta >= theta*, AvHvPersuadable), highest first.
std::vector<double> Candidates(const MultiReceiverProblem& problem, const LikelihoodModel& model) {
  std::vector<double> candidates;
  for (double theta : problem.design_trusts) {
    if (AvHvPersuadable(problem.params, theta, model)) candidates.push_back(theta);
  }
  std::sort(candidates.begin(), candidates.end(), std::greater<double>());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  return candidates;
}

std::string Why(const MultiReceiverDesign& design, int n, int persuadable) {
  if (design.status == MultiReceiverStatus::kAddressesNone) {
    return "no HV's design trust reaches theta* = " + NumberText(design.design.theta_star) +
           ": no nudge, the AV always yields";
  }
  std::string why = "addresses " + std::to_string(design.addressed_count) + " of " +
                    std::to_string(n) + " HVs (designed for trust tau = " +
                    NumberText(design.designed_for) + ", b = " + NumberText(design.design.b) + ")";
  if (persuadable > design.addressed_count) {
    why += "; gives up " + std::to_string(persuadable - design.addressed_count) +
           " persuadable HV(s) for a larger b";
  }
  if (n > persuadable) {
    why += "; " + std::to_string(n - persuadable) + " HV(s) below theta* = " +
           NumberText(design.design.theta_star);
  }
  if (design.status == MultiReceiverStatus::kAddressesSome) {
    why += "; the AV yields (an HV of the meeting drives recklessly)";
  }
  return why;
}

}  // namespace

const char* ToString(MultiReceiverStatus status) {
  switch (status) {
    case MultiReceiverStatus::kAddressesAll:
      return "addresses all";
    case MultiReceiverStatus::kAddressesSome:
      return "addresses some";
    case MultiReceiverStatus::kAddressesNone:
      return "addresses none";
  }
  return "unknown";
}

bool MultiReceiverProblem::IsValid(std::string* why) const {
  std::string message;
  if (!params.IsValid(&message)) {
    if (why != nullptr) *why = "params: " + message;
    return false;
  }
  message = TrustListProblem(design_trusts, "design_trusts");
  if (!message.empty()) {
    if (why != nullptr) *why = message;
    return false;
  }
  return true;
}

void MultiReceiverProblem::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

// Every candidate tau is scored by what the common scheme DesignTaebp(tau)
// does to every HV at its design trust (PredictOutcome). For lambda < p* the
// HVs at or above tau drive if clear after the nudge and the rest never do;
// for lambda >= p* the highest trust's design persuades everyone (the
// doc's section 5). The best score wins, ties to the lower tau (more HVs
// addressed). An HV is addressed when it drives if clear after the nudge.
MultiReceiverDesign DesignMultiReceiver(const MultiReceiverProblem& problem,
                                        const LikelihoodModel& model) {
  problem.Validate();
  const AvHvParams& params = problem.params;
  const std::vector<double>& trusts = problem.design_trusts;
  const int n = static_cast<int>(trusts.size());
  MultiReceiverDesign result;
  result.candidates = Candidates(problem, model);
  double best_value = 0.0;
  for (double tau : result.candidates) {
    const CommittedScheme scheme = SchemeOf(DesignTaebp(params, tau, model));
    const double value = SenderValue(PerReceiver(scheme, params, trusts, model));
    result.candidate_values.push_back(value);
    if (result.candidate_values.size() == 1 || value >= best_value) {
      best_value = value;
      result.designed_for = tau;
    }
  }
  // No candidate: the design for the lowest trust, which is not persuadable
  // (the paper's fallback), keeps theta* and p* in the result.
  const double design_for = result.candidates.empty()
                                ? *std::min_element(trusts.begin(), trusts.end())
                                : result.designed_for;
  result.design = DesignTaebp(params, design_for, model);
  result.scheme = SchemeOf(result.design);
  result.addressed.assign(n, false);
  int persuadable = 0;
  if (!result.candidates.empty()) {
    for (int i = 0; i < n; ++i) {
      result.addressed[i] = DrivesIfClearAfterNudge(result.scheme, params, trusts[i], model);
      result.addressed_count += result.addressed[i] ? 1 : 0;
      persuadable += trusts[i] >= result.candidates.back() ? 1 : 0;
    }
    result.status = result.addressed_count == n ? MultiReceiverStatus::kAddressesAll
                                                : MultiReceiverStatus::kAddressesSome;
  }
  // The AV goes on its Go intent only when no HV of the meeting is given up.
  result.scheme.av_may_go = result.status == MultiReceiverStatus::kAddressesAll;
  result.predicted = PerReceiver(result.scheme, params, trusts, model);
  result.sender_value = SenderValue(result.predicted);
  result.why = Why(result, n, persuadable);
  return result;
}

// Each HV's reaction to a magnitude s is deterministic (HvDrivesIfClear), so a
// collision with some HV happens when the AV goes (Go intent, av_may_go) and
// the signal it showed -- the nudge (probability a) or standing still -- leaves
// at least one HV driving recklessly. A random magnitude is averaged over its
// uniform law like PredictOutcome does.
MultiReceiverOutcome PredictMultiReceiver(const CommittedScheme& scheme, const AvHvParams& params,
                                          const std::vector<double>& true_trusts,
                                          const LikelihoodModel& model) {
  params.Validate();
  const std::string bad = TrustListProblem(true_trusts, "true_trusts");
  if (!bad.empty()) throw InvalidArgument(bad);
  MultiReceiverOutcome outcome;
  outcome.per_receiver = PerReceiver(scheme, params, true_trusts, model);
  outcome.sender_value = SenderValue(outcome.per_receiver);
  if (!scheme.av_may_go) return outcome;
  auto all_dc = [&](double s) {
    for (double theta : true_trusts) {
      if (!HvDrivesIfClear(params, HvPosteriorGo(scheme, params, theta, model, s))) return false;
    }
    return true;
  };
  const double all_dc_nudge = scheme.random_magnitude
                                  ? internal::ShareWhere(all_dc, 0.0, scheme.nudge)
                                  : (all_dc(scheme.nudge) ? 1.0 : 0.0);
  const double all_dc_still = all_dc(0.0) ? 1.0 : 0.0;
  outcome.any_collision_rate =
      params.prior_go * (1.0 - (scheme.a * all_dc_nudge + (1.0 - scheme.a) * all_dc_still));
  return outcome;
}

}  // namespace taebp::persuasion
