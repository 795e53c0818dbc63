// The HV's intuitive likelihood of an embodied signal (a forward nudge of s
// metres, s in [0, s_max]) given the AV's intent (paper Section IV-B).
#pragma once

#include <memory>
#include <string>

namespace taebp::persuasion {

class LikelihoodModel {
 public:
  virtual ~LikelihoodModel() = default;
  virtual std::string Name() const = 0;
  double SMax() const { return s_max_; }
  // pi(s | Go), increasing in s; pi(s | Stop), decreasing in s.
  // Both throw InvalidArgument when s is outside [0, s_max].
  virtual double PiGo(double s) const = 0;
  virtual double PiStop(double s) const = 0;
  // L(s) = pi(s|Go) / pi(s|Stop); +infinity where pi(s|Stop) = 0.
  double Ratio(double s) const;
  // L^{-1}(ratio): the smallest s in [0, s_max] with L(s) >= ratio.
  //   ratio <= L(0) (in particular ratio <= 0) -> 0 (no nudge needed);
  //   ratio = +infinity -> s_max when L(s_max) = +infinity;
  //   ratio > L(s_max) -> throws InvalidArgument (unreachable; this includes
  //   ratio = +infinity for a bounded L such as the logistic model);
  //   ratio = NaN -> throws InvalidArgument.
  virtual double InverseRatio(double ratio) const = 0;
  // Largest reachable ratio L(s_max) (may be +infinity).
  double MaxRatio() const { return Ratio(s_max_); }

 protected:
  explicit LikelihoodModel(double s_max);  // throws unless s_max > 0 and finite
  void CheckSignal(double s) const;        // throws unless 0 <= s <= s_max
  double s_max_;
};

// The paper's model: pi(s|Go) = s/s_max, pi(s|Stop) = 1 - s/s_max,
// L(s) = s / (s_max - s), L^{-1}(R) = s_max R / (1 + R) in closed form.
class LinearLikelihood final : public LikelihoodModel {
 public:
  explicit LinearLikelihood(double s_max = 2.0);
  std::string Name() const override { return "linear"; }
  double PiGo(double s) const override;
  double PiStop(double s) const override;
  double InverseRatio(double ratio) const override;
};

// Logistic model: pi(s|Go) = sigma(k (s - m)), pi(s|Stop) = 1 - pi(s|Go),
// with steepness k > 0 and midpoint m in [0, s_max]. L(s_max) is finite, so
// some ratios are unreachable. InverseRatio uses bracketed root finding
// (Boost.Math TOMS 748) to an absolute tolerance in s of kInverseTolerance.
class LogisticLikelihood final : public LikelihoodModel {
 public:
  static constexpr double kInverseTolerance = 1e-12;
  LogisticLikelihood(double s_max, double steepness, double midpoint);
  std::string Name() const override { return "logistic"; }
  double PiGo(double s) const override;
  double PiStop(double s) const override;
  double InverseRatio(double ratio) const override;
  double Steepness() const { return k_; }
  double Midpoint() const { return m_; }

 private:
  double k_, m_;
};

}  // namespace taebp::persuasion
