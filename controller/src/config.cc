#include "taebp/controller/config.h"

#include <cmath>
#include <set>
#include <sstream>

namespace taebp {
namespace {

std::string Num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

// Collects the first failure; keeps IsValid readable.
class Checker {
 public:
  explicit Checker(std::string* why) : why_(why) {}
  bool ok() const { return ok_; }
  void Fail(const std::string& msg) {
    if (!ok_) return;
    ok_ = false;
    if (why_) *why_ = msg;
  }
  void Positive(const char* key, double v) {
    if (!(std::isfinite(v) && v > 0)) Fail(std::string(key) + " = " + Num(v) + " must be > 0");
  }
  void NonNegative(const char* key, double v) {
    if (!(std::isfinite(v) && v >= 0)) Fail(std::string(key) + " = " + Num(v) + " must be >= 0");
  }
  void Closed01(const char* key, double v) {
    if (!(v >= 0.0 && v <= 1.0)) Fail(std::string(key) + " = " + Num(v) + " is outside [0, 1]");
  }
  void Open01(const char* key, double v) {
    if (!(v > 0.0 && v < 1.0)) Fail(std::string(key) + " = " + Num(v) + " is outside (0, 1)");
  }

 private:
  std::string* why_;
  bool ok_ = true;
};

}  // namespace

bool ExperimentConfig::IsValid(std::string* why) const {
  Checker c(why);
  const ScenarioConfig& s = scenario;
  if (s.avs < 0) c.Fail("scenario.avs = " + std::to_string(s.avs) + " must be >= 0");
  if (s.hvs < 0) c.Fail("scenario.hvs = " + std::to_string(s.hvs) + " must be >= 0");
  if (s.avs >= 0 && s.hvs >= 0 && s.avs + s.hvs == 0)
    c.Fail("scenario.avs + scenario.hvs = 0: the scenario needs at least one vehicle");
  c.Positive("scenario.cruise_speed", s.cruise_speed);
  c.NonNegative("scenario.min_gap", s.min_gap);
  c.Positive("scenario.stop_distance", s.stop_distance);
  c.Positive("scenario.step_length", s.step_length);
  if (c.ok() && s.step_length > 1.0)
    c.Fail("scenario.step_length = " + Num(s.step_length) + " must be <= 1 s");
  c.Positive("scenario.duration", s.duration);
  if (c.ok() && s.duration < s.step_length)
    c.Fail("scenario.duration = " + Num(s.duration) + " is shorter than one step");
  c.Positive("scenario.vehicle_length", s.vehicle_length);
  c.Positive("scenario.vehicle_width", s.vehicle_width);
  c.Positive("scenario.accel", s.accel);
  c.Positive("scenario.decel", s.decel);
  c.NonNegative("scenario.arrival_window", s.arrival_window);
  c.NonNegative("scenario.confirm_delay", s.confirm_delay);
  c.Positive("scenario.creep_speed", s.creep_speed);
  c.Positive("scenario.loop_length", s.loop_length);

  const ModelConfig& m = model;
  c.Open01("model.prior_go", m.prior_go);
  c.Positive("model.collision_penalty", m.collision_penalty);
  c.Closed01("model.trust", m.trust);
  if (m.assumed_trust) c.Closed01("model.assumed_trust", *m.assumed_trust);
  const LikelihoodConfig& l = m.likelihood;
  if (l.type != "linear" && l.type != "logistic")
    c.Fail("model.likelihood.type = '" + l.type + "' is not one of: linear, logistic");
  c.Positive("model.likelihood.s_max", l.s_max);
  if (l.type == "logistic") {
    c.Positive("model.likelihood.steepness", l.steepness);
    if (!(l.midpoint >= 0 && l.midpoint <= l.s_max))
      c.Fail("model.likelihood.midpoint = " + Num(l.midpoint) + " is outside [0, s_max]");
  }
  if (c.ok() && l.s_max >= s.stop_distance + 50.0)
    c.Fail("model.likelihood.s_max = " + Num(l.s_max) + " is not a nudge (> 50 m past the stop)");

  if (policies.empty()) c.Fail("policies is empty: list at least one of no_ebp, no_trust, ta_ebp, full_reveal");
  std::set<std::string> seen;
  for (const std::string& p : policies) {
    if (p != "no_ebp" && p != "no_trust" && p != "ta_ebp" && p != "full_reveal")
      c.Fail("policies: '" + p + "' is not one of no_ebp, no_trust, ta_ebp, full_reveal");
    if (!seen.insert(p).second) c.Fail("policies: '" + p + "' is listed twice");
  }
  return c.ok();
}

}  // namespace taebp
