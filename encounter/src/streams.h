// The HV population's own random numbers (hv_population.h "Randomness"):
// the seeds of its streams and the draws keyed by a vehicle's id. Private to
// the encounter room.
#pragma once

#include <cstdint>
#include <string>

namespace taebp::streams {

// Seeds of the population's own streams: scenario.seed mixed with a salt per
// purpose (splitmix64), so the streams are independent of each other and of
// the controller's encounter stream (std::mt19937_64(seed)).
std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t salt);

// A uniform in [0, 1) from a vehicle id (FNV-1a), the seed and a salt: the
// same id, seed and salt give the same draw in every policy's run.
double IdUniform(std::uint64_t seed, const std::string& id, std::uint64_t salt);

inline constexpr std::uint64_t kSaltNoise = 0x6e6f697365;  // "noise": the HVs' readings
inline constexpr std::uint64_t kSaltProbe = 0x70726f6265;  // "probe": ta_ebp_learned
inline constexpr std::uint64_t kSaltMagnitude = 0x6d61676e;  // "magn": random_nudge
inline constexpr std::uint64_t kSaltStrength = 0x6b;  // "k": each HV's prior strength

}  // namespace taebp::streams
