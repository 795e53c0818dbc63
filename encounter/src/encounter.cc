#include "taebp/encounter/encounter.h"

#include <algorithm>
#include <cmath>

namespace taebp {

double Uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

AvDraw DrawAv(const persuasion::CommittedScheme& scheme, double prior_go, std::mt19937_64& rng) {
  AvDraw d;
  const double u_intent = Uniform01(rng);
  const double u_signal = Uniform01(rng);
  d.intent_go = u_intent < prior_go;
  const double p_nudge = d.intent_go ? scheme.a : scheme.b;
  d.nudge = scheme.nudge > 0.0 && u_signal < p_nudge;
  d.nudge_distance = d.nudge ? scheme.nudge : 0.0;
  d.goes_first = d.intent_go && scheme.av_may_go;
  return d;
}

HvReading ReadNudge(const persuasion::CommittedScheme& scheme,
                    const persuasion::AvHvParams& params, double theta,
                    const persuasion::LikelihoodModel& model, double observed) {
  HvReading r;
  r.observed = observed;
  const double s = std::clamp(observed, 0.0, model.SMax());
  r.posterior = persuasion::HvPosteriorGo(scheme, params, theta, model, s);
  r.drives_if_clear = persuasion::HvDrivesIfClear(params, r.posterior);
  return r;
}

EncounterSequence::EncounterSequence(bool av_goes, bool hv_drives_if_clear, double decided_at,
                                     double confirm_delay)
    : av_goes_(av_goes),
      hv_dc_(hv_drives_if_clear),
      decided_at_(decided_at),
      confirm_delay_(confirm_delay) {}

std::vector<EncounterSequence::Release> EncounterSequence::Update(double now, bool av_entered,
                                                                  bool hv_entered,
                                                                  bool av_may_enter,
                                                                  bool hv_may_enter,
                                                                  bool av_may_go,
                                                                  bool hv_may_go) {
  std::vector<Release> out;
  auto release = [&](bool av, bool reckless) {
    if (!(av ? av_may_go : hv_may_go)) return;                     // its way: later
    if (!reckless && !(av ? av_may_enter : hv_may_enter)) return;  // keep clear: later
    out.push_back({av, reckless});
    (av ? av_released_ : hv_released_) = true;
  };
  if (av_goes_) {
    if (!av_released_) release(true, false);
    if (!hv_released_) {
      if (!hv_dc_) release(false, true);
      else if (av_entered) release(false, false);
    }
  } else {
    if (!hv_released_) {
      if (!hv_dc_) release(false, true);
      else if (now >= decided_at_ + confirm_delay_ - 1e-9) release(false, false);
    }
    if (!av_released_ && hv_entered) release(true, false);
  }
  return out;
}

bool NudgeRealised(double commanded, double observed, double tolerance) {
  if (commanded > 0)
    return observed >= commanded - 1e-9 && observed <= commanded + tolerance;
  return std::abs(observed) <= tolerance;
}

double CreepSpeed(double target, double covered, double speed, double dt, double accel,
                  double decel, double creep_speed) {
  const double remaining = target - covered;
  if (remaining <= 1e-12) return 0.0;
  const double v_accel = std::min(creep_speed, speed + accel * dt);
  // Largest v from which the vehicle can still stop within the target when each
  // step's speed drops by at most dv = decel*dt: the steps v, v - dv, v - 2dv, ...
  // cover dt * S(v), S(v) = sum_k max(0, v - k dv), piecewise linear in v with
  // S(m dv) = dv m(m+1)/2. (The continuous bound v*dt/2 + v^2/(2 decel) <=
  // remaining agrees with S at the grid points but lies below it in between, so
  // it allows speeds that then need more than `decel` to land.)
  const double dv = decel * dt;
  const double budget = remaining / dt;  // S(v) may not exceed this
  double m = std::floor((std::sqrt(1.0 + 8.0 * budget / dv) - 1.0) / 2.0);
  while (m > 0 && dv * m * (m + 1) / 2 > budget) m -= 1;  // round-off guards
  while (dv * (m + 1) * (m + 2) / 2 <= budget) m += 1;
  const double v_brake = (budget + dv * m * (m + 1) / 2) / (m + 1);
  const double v_land = remaining / dt;
  return std::max(0.0, std::min({v_accel, v_brake, v_land}));
}

}  // namespace taebp
