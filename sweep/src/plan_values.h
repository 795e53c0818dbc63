// Text helpers the sweep's plan, journal and tables share (plan.cc).
#pragma once

#include "taebp/sweep/plan.h"

#include <string>

namespace taebp::sweep::internal {

// `s` without leading and trailing blanks (space, tab, CR, LF).
std::string Trim(const std::string& s);

// A grid value as JSON with its YAML type (results.jsonl, sweep.json):
// 0.5 -> 0.5, ta_ebp -> "ta_ebp", [8, 8] -> [8, 8]; unparsable text stays text.
Json ValueJson(const std::string& text);

}  // namespace taebp::sweep::internal
