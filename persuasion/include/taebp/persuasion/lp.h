// The trust-aware optimal signaling scheme for any finite game, as a linear
// program solved with GLPK.
//
// By the revelation principle the signals are action recommendations: pi(a|w).
// With P(a) = sum_w pi(a|w) p0(w), the trust-weighted posterior after
// recommendation a is p_theta(w|a) = (1-theta) p0(w) + theta pi(a|w) p0(w) / P(a).
// Obedience, sum_w p_theta(w|a) (u(w,a) - u(w,a')) >= 0 for all a', is not linear
// in pi, but multiplying it by P(a) >= 0 gives
//   sum_w [ (1-theta) p0(w) P(a) + theta pi(a|w) p0(w) ] (u(w,a) - u(w,a')) >= 0,
// which is linear in pi because P(a) is. (When P(a) = 0 the action is never
// recommended and the constraint is vacuous, as it should be.)
// Maximise sum_w p0(w) sum_a pi(a|w) v(w,a) subject to obedience, sum_a pi(a|w) = 1
// and pi >= 0.
//
// Numerics and size (details in lp.cc): obedience rows are built from utility
// differences (never a difference of two large expected utilities), both tables
// are scaled by a power of two so any finite entries work (+-1e308 included),
// GLPK's fatal errors come back as kSolverError instead of aborting the
// process, and obedience rows are generated lazily. Measured on this project's
// shared 2-core machine (bench/lp_scaling: random games, theta = 0.7; n x m =
// states x actions): 50 x 50 ~0.1 s, 100 x 100 ~1-1.5 s (the full LP,
// LpOptions::lazy_obedience = false: ~1.5 s and 87-103 s), and at the limits 200 x 200 ~12 s, 400 x 100 ~15 s, 100 x 400 ~9 s,
// 10000 x 4 ~9 s, 2 x 2000 ~2 s. Larger games are refused (kMaxLpVariables,
// kMaxLpObedienceEntries) with an error naming their size.
#pragma once

#include "taebp/persuasion/persuasion.h"

#include <string>
#include <vector>

namespace taebp::persuasion {

struct LpResult {
  enum class Status { kOptimal, kInfeasible, kSolverError };
  Status status = Status::kSolverError;
  std::string message;          // solver detail when not optimal (GLPK's own text on an error)
  double sender_value = 0.0;    // sum_w p0(w) sum_a pi(a|w) v(w,a)
  Eigen::MatrixXd scheme;       // n x m: pi(recommend a | w)
  Eigen::VectorXd signal_probability;  // m: P(a)
  // Column a: the trust-weighted posterior after recommendation a (n entries);
  // NaN for actions recommended with probability 0.
  Eigen::MatrixXd posteriors;
  int simplex_rounds = 0;   // glp_simplex calls (1 + cutting-plane rounds)
  int obedience_rows = 0;   // obedience rows in the final LP (of m (m - 1))
  // Recommendations GLPK's round-off left disobedient beyond kObedienceTolerance
  // at their own posterior, merged into the receiver's best response there
  // (persuasion.h, the tolerance policy); they are always rare (tiny P(a)).
  int merged_recommendations = 0;
};

const char* ToString(LpResult::Status status);

struct LpOptions {
  // true: generate obedience rows as the solution violates them (fast, same
  // optimum); false: all m (m - 1) rows at once (the reference formulation).
  bool lazy_obedience = true;
};

// The largest game SolveTrustAwarePersuasion accepts: n m scheme entries (the
// LP's columns; 200 x 200 is ~15 s) and n m (m - 1) obedience coefficients
// (held in memory, 8 bytes each: 128 MB). Above either it throws
// InvalidArgument naming the size instead of running for minutes or hours.
inline constexpr double kMaxLpVariables = 40000;
inline constexpr double kMaxLpObedienceEntries = 16e6;

// theta in [0, 1]; the game is validated first (throws InvalidArgument, also
// when n m > kMaxLpVariables). GLPK failures are reported in the result.
LpResult SolveTrustAwarePersuasion(const Game& game, double theta, const LpOptions& options = {});

// Runs call(arg) with GLPK's error hook set: a fatal GLPK error (which would
// otherwise abort() the process) longjmps back here, GLPK's environment is
// freed (every GLPK object of this thread: call must create and delete its
// own) and false is returned with GLPK's message in *error. call must not
// keep objects with destructors on its stack while it calls GLPK. Output GLPK
// prints during the call is captured rather than printed.
bool RunGlpkGuarded(void (*call)(void*), void* arg, std::string* error);

}  // namespace taebp::persuasion
