// A portable uniform draw for the SUMO-free simulations and per-encounter
// draws of the persuasion models, and the Beta quantile that turns one into a
// trust. The standard distributions
// (std::uniform_real_distribution, std::normal_distribution) are
// implementation-defined; this is not: the top 53 bits of one 64-bit
// Mersenne-twister output, scaled to [0, 1). Same as controller's Uniform01.
#pragma once

#include <random>

namespace taebp::persuasion {

inline double Uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// The quantile of Beta(alpha, beta) at q in (0, 1) (the inverse of the
// regularised incomplete beta function, Boost.Math's ibeta_inv): a trust drawn
// from a Beta distribution by inversion (config's TrustSpec::Quantile).
double BetaQuantile(double alpha, double beta, double q);

}  // namespace taebp::persuasion
