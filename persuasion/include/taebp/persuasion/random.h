// A portable uniform draw for the SUMO-free simulations and per-encounter
// draws of the persuasion models. The standard distributions
// (std::uniform_real_distribution, std::normal_distribution) are
// implementation-defined; this is not: the top 53 bits of one 64-bit
// Mersenne-twister output, scaled to [0, 1). Same as controller's Uniform01.
#pragma once

#include <random>

namespace taebp::persuasion {

inline double Uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

}  // namespace taebp::persuasion
