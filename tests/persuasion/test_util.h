// Shared helpers for the persuasion tests.
#pragma once

#include "taebp/persuasion/persuasion.h"

#include <gtest/gtest.h>

#include "test_support.h"

#include <string>
#include <utility>

namespace taebp::persuasion::testing {

// Runs f, expecting it to throw InvalidArgument; returns e.what() (or "" after
// recording a failure), to be checked with EXPECT_THAT(..., HasSubstr(...)).
template <typename F>
std::string InvalidArgumentMessage(F&& f) {
  return taebp::test::ErrorOf<InvalidArgument>(std::forward<F>(f));
}

}  // namespace taebp::persuasion::testing
