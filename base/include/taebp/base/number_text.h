// Numbers as text: the project's one formatter. Every file, message and
// generated SUMO input writes a double through one of these two (tests/layers
// fails on another formatter: a std::to_chars, a stream precision or a %g
// outside base/src/number_text.cc).
#pragma once

#include <string>

namespace taebp {

// The shortest decimal text that reads back as exactly `v` ("0.9", "-0.2",
// "1e-07", "nan", "inf"): result files, and messages that quote a value as
// it was given.
std::string NumberText(double v);

// `v` to `significant` significant digits, trailing zeros dropped, as
// printf's "%.*g" ("160.531", "1e+06", "nan"): messages about computed values
// (6), config values in messages (10), numbers handed to SUMO (17, exact).
std::string NumberText(double v, int significant);

}  // namespace taebp
