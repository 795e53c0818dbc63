// Private helpers shared by the persuasion sources (not installed, not public).
#pragma once

#include "taebp/persuasion/number_text.h"
#include "taebp/persuasion/persuasion.h"

#include <cmath>
#include <string>

namespace taebp::persuasion::internal {

// theta in [0, 1] (NaN rejected).
inline void CheckTrust(double theta, const char* name = "trust theta") {
  if (!(theta >= 0.0 && theta <= 1.0)) {
    throw InvalidArgument(std::string(name) + " = " + NumberText(theta) + " is outside [0, 1]");
  }
}

}  // namespace taebp::persuasion::internal
