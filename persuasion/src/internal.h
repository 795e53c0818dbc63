// Private helpers shared by the persuasion sources (not installed, not public).
#pragma once

#include "taebp/persuasion/persuasion.h"

#include <charconv>
#include <cmath>
#include <string>

namespace taebp::persuasion::internal {

// Shortest decimal text that round-trips to `value` ("0.9", "-0.2", "1.3",
// "nan", "inf"), so error messages quote exactly what the caller passed.
inline std::string Num(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// theta in [0, 1] (NaN rejected).
inline void CheckTrust(double theta, const char* name = "trust theta") {
  if (!(theta >= 0.0 && theta <= 1.0)) {
    throw InvalidArgument(std::string(name) + " = " + Num(theta) + " is outside [0, 1]");
  }
}

}  // namespace taebp::persuasion::internal
