// The exception being handled as the program reports it: its kind
// (base/exit_codes.h), the line for stderr and the exit code. The CLI's
// ReportErrors, the Python module's sweep tasks and its exception translator
// use it, so a kind has one exit code and one message everywhere.
#pragma once

#include "taebp/base/exit_codes.h"

#include <exception>
#include <string>

namespace taebp {

struct ErrorReport {
  ErrorKind kind = ErrorKind::kOther;
  int exit_code = kExitFailed;
  std::string message;  // what()
  std::string line;     // "taebp: config error: ...", as stderr shows it (no newline)
};

// Classifies `error` (a std::exception or not).
ErrorReport ReportOf(std::exception_ptr error);

}  // namespace taebp
