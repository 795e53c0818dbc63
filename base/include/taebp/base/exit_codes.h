// The program's exit codes and the kinds of error behind them, written once:
// the CLI (tools/cli), the sweep engine (a task's and the sweep's own code)
// and the Python module (each exception's `exit_code`) read them here. The
// README's table "Exit codes" says the same; tests/cli/exit_codes_test.cc and
// tests/python/test_exit_codes.py compare. Which C++ exception is which kind:
// runner/errors.h (ErrorKindOf).
#pragma once

#include <vector>

namespace taebp {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;     // anything else; a failed or missing sweep task
inline constexpr int kExitConfig = 2;     // bad configuration, argument or --out
inline constexpr int kExitSumo = 3;       // SUMO failed
inline constexpr int kExitStall = 4;      // stall_action: error stopped the experiment
inline constexpr int kExitSignalBase = 128;  // interrupted: 128 + the signal's number
inline constexpr int kExitInterrupted = kExitSignalBase + 2;  // SIGINT (Ctrl-C): 130

enum class ErrorKind { kConfig, kInvalidArgument, kOutput, kSumo, kStall, kBusy, kInterrupted, kOther };

struct ErrorKindInfo {
  ErrorKind kind;
  const char* python_name;  // the exception's name in the Python module
  const char* prefix;       // after "taebp: " on stderr ("" for none)
  int exit_code;            // kInterrupted: 128 + the signal (kExitInterrupted for Ctrl-C)
};

inline const std::vector<ErrorKindInfo>& ErrorKinds() {
  static const std::vector<ErrorKindInfo> kinds = {
      {ErrorKind::kConfig, "ConfigError", "config error: ", kExitConfig},
      {ErrorKind::kInvalidArgument, "InvalidArgument", "invalid argument: ", kExitConfig},
      {ErrorKind::kOutput, "OutputError", "", kExitConfig},
      {ErrorKind::kSumo, "SumoError", "", kExitSumo},
      {ErrorKind::kStall, "StallError", "stalled: ", kExitStall},
      {ErrorKind::kBusy, "SimulationBusy", "error: ", kExitFailed},
      {ErrorKind::kInterrupted, "Interrupted", "", kExitInterrupted},
      {ErrorKind::kOther, "Error", "error: ", kExitFailed},
  };
  return kinds;
}

inline const ErrorKindInfo& ErrorKindOf(ErrorKind kind) {
  for (const ErrorKindInfo& k : ErrorKinds())
    if (k.kind == kind) return k;
  return ErrorKinds().back();
}

}  // namespace taebp
