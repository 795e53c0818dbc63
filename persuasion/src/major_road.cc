// The major-road encounter: the paper's game with a yielding cost, expressed
// through the paper's functions at the equivalent penalty r_eff, and the
// kinematic window in which an approach is that game. See docs/beyond/major-road.md.
#include "taebp/persuasion/major_road.h"

#include "internal.h"

#include <cmath>
#include <string>

namespace taebp::persuasion {


bool MajorRoadParams::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(prior_go > 0.0 && prior_go < 1.0)) {
    return fail("prior_go (lambda) = " + NumberText(prior_go) + " is outside (0, 1)");
  }
  if (!(collision_penalty > 0.0) || !std::isfinite(collision_penalty)) {
    return fail("collision_penalty r = " + NumberText(collision_penalty) + " must be > 0 and finite");
  }
  if (!(yield_cost >= 0.0) || !std::isfinite(yield_cost)) {
    return fail("yield_cost c = " + NumberText(yield_cost) + " must be >= 0 and finite");
  }
  if (!(yield_cost < collision_penalty)) {
    return fail("yield_cost c = " + NumberText(yield_cost) + " must be < collision_penalty r = " +
                NumberText(collision_penalty) +
                " (otherwise keeping its way is weakly dominant: the HV never yields)");
  }
  return true;
}

void MajorRoadParams::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

// u_major = k u_paper(r_eff) + h(w): the gains of DC over DR are (r - c, -(2 + c))
// against the paper's (r_eff, -2), equal up to k = (2 + c)/2 iff r_eff = 2(r - c)/(2 + c).
double MajorRoadEffectivePenalty(const MajorRoadParams& params) {
  params.Validate();
  const double r = params.collision_penalty;
  const double c = params.yield_cost;
  return 2.0 * (r - c) / (2.0 + c);
}

AvHvParams MajorRoadParams::EquivalentPaperParams() const {
  AvHvParams paper;
  paper.prior_go = prior_go;
  paper.collision_penalty = MajorRoadEffectivePenalty(*this);  // validates
  return paper;
}

// Rows (Go, Stop), columns (DR, DC).
//   u: DR -> (-r, 1), DC -> (-c, -1 - c);  v: DR -> (-1, -1), DC -> (1, 1).
Game MajorRoadGame(const MajorRoadParams& params) {
  params.Validate();
  const double r = params.collision_penalty;
  const double c = params.yield_cost;
  Game game;
  game.states = {"Go", "Stop"};
  game.actions = {"DR", "DC"};
  game.prior = Eigen::Vector2d(params.prior_go, 1.0 - params.prior_go);
  game.receiver_utility.resize(2, 2);
  game.receiver_utility << -r, -c,  //
      1.0, -1.0 - c;
  game.sender_utility.resize(2, 2);
  game.sender_utility << -1.0, 1.0,  //
      -1.0, 1.0;
  return game;
}

// eq:ppp: p* = (u(Stop,DC) - u(Stop,DR)) / (u(Go,DR) - u(Go,DC) - u(Stop,DR) + u(Stop,DC))
//            = (-1 - c - 1) / (-r + c - 1 - 1 - c) = (2 + c)/(2 + r), i.e. 2/(2 + r_eff).
double MajorRoadPStar(const MajorRoadParams& params) {
  return AvHvPStar(params.EquivalentPaperParams().collision_penalty);
}

double MajorRoadThetaStar(const MajorRoadParams& params) {
  return AvHvThetaStar(params.EquivalentPaperParams());
}

bool MajorRoadHvYields(const MajorRoadParams& params, double p_go) {
  return HvDrivesIfClear(params.EquivalentPaperParams(), p_go);
}

TaebpDesign DesignMajorRoad(const MajorRoadParams& params, double theta_hat,
                            const LikelihoodModel& model) {
  return DesignTaebp(params.EquivalentPaperParams(), theta_hat, model);
}

CommittedScheme CommitMajorRoadScheme(Policy policy, const MajorRoadParams& params,
                                      double theta_hat, const LikelihoodModel& model) {
  return CommitScheme(policy, params.EquivalentPaperParams(), theta_hat, model);
}

PredictedOutcome PredictMajorRoadOutcome(Policy policy, const MajorRoadParams& params,
                                         double theta_true, const LikelihoodModel& model,
                                         std::optional<double> theta_hat) {
  return PredictOutcome(policy, params.EquivalentPaperParams(), theta_true, model, theta_hat);
}

// ---------------------------------------------------------------------------
// When an approach is the game.
// ---------------------------------------------------------------------------
bool MajorRoadApproach::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  const struct {
    const char* name;
    double value;
    bool positive;  // > 0 required (else >= 0)
  } fields[] = {
      {"hv_distance", hv_distance, false},
      {"hv_speed", hv_speed, true},
      {"comfortable_deceleration", comfortable_deceleration, true},
      {"reaction_time", reaction_time, false},
      {"hv_occupancy_length", hv_occupancy_length, false},
      {"av_enter_time", av_enter_time, false},
      {"av_clear_time", av_clear_time, false},
  };
  for (const auto& field : fields) {
    const std::string text = std::string(field.name) + " = " + NumberText(field.value);
    if (!std::isfinite(field.value)) return fail(text + " must be finite");
    if (field.positive && !(field.value > 0.0)) return fail(text + " must be > 0");
    if (!field.positive && !(field.value >= 0.0)) return fail(text + " must be >= 0");
  }
  if (!(av_clear_time > av_enter_time)) {
    return fail("av_clear_time = " + NumberText(av_clear_time) + " must be > av_enter_time = " +
                NumberText(av_enter_time) + " (the AV's crossing takes time)");
  }
  return true;
}

void MajorRoadApproach::Validate() const {
  std::string why;
  if (!IsValid(&why)) throw InvalidArgument(why);
}

const char* ToString(ApproachKind kind) {
  switch (kind) {
    case ApproachKind::kHvPassesFirst:
      return "hv_passes_first";
    case ApproachKind::kAvClearsFirst:
      return "av_clears_first";
    case ApproachKind::kCannotYield:
      return "cannot_yield";
    case ApproachKind::kGame:
      return "game";
  }
  return "unknown";
}

// Under DR the HV's front is in the zone during (d/v, (d + l)/v), the AV during
// (t_in, t_out): they collide iff v t_in - l < d < v t_out. Yielding: the HV keeps
// v until t_r, then brakes at a (to a stop at most); its front must not reach the
// zone before t_out: x(t_out) <= d with
//   x(T) = v T                               T <= t_r
//        = v t_r + v tau - a tau^2 / 2       tau = T - t_r <= v / a
//        = v t_r + v^2 / (2a)                tau >= v / a (stopped).
ApproachWindow ClassifyMajorRoadApproach(const MajorRoadApproach& approach) {
  approach.Validate();
  const double d = approach.hv_distance;
  const double v = approach.hv_speed;
  const double a = approach.comfortable_deceleration;
  const double t_r = approach.reaction_time;
  ApproachWindow window;
  window.time_to_arrival = d / v;
  window.conflict_min_distance = v * approach.av_enter_time - approach.hv_occupancy_length;
  window.conflict_max_distance = v * approach.av_clear_time;
  window.stopping_distance = v * t_r + v * v / (2.0 * a);
  const double tau = approach.av_clear_time - t_r;
  if (tau <= 0.0) {
    window.yield_distance = v * approach.av_clear_time;
  } else if (a * tau >= v) {
    window.yield_distance = window.stopping_distance;
  } else {
    window.yield_distance = v * t_r + v * tau - 0.5 * a * tau * tau;
  }
  if (d <= window.conflict_min_distance) {
    window.kind = ApproachKind::kHvPassesFirst;
  } else if (d >= window.conflict_max_distance) {
    window.kind = ApproachKind::kAvClearsFirst;
  } else if (d < window.yield_distance) {
    window.kind = ApproachKind::kCannotYield;
  } else {
    window.kind = ApproachKind::kGame;
  }
  return window;
}

}  // namespace taebp::persuasion
