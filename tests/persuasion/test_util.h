// Shared helpers for the persuasion tests.
#pragma once

#include "taebp/persuasion/persuasion.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

namespace taebp::persuasion::testing {

// Runs f, expecting it to throw InvalidArgument; returns e.what() (or "" after
// recording a failure), to be checked with EXPECT_THAT(..., HasSubstr(...)).
template <typename F>
std::string InvalidArgumentMessage(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const InvalidArgument& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InvalidArgument, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected InvalidArgument, nothing was thrown";
  return "";
}

}  // namespace taebp::persuasion::testing
