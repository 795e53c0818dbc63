// runner/errors.h: how the program reports the exception being handled (the
// CLI's exit code and stderr line, the Python module's exception). The codes
// expected here are written out as the README's "Exit codes" table states
// them, not read from exit_codes.h, so a change of either shows.
#include "taebp/runner/errors.h"

#include "taebp/config/config.h"
#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/persuasion/persuasion.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/runner/runner.h"

#include <gtest/gtest.h>

#include <csignal>
#include <exception>
#include <stdexcept>
#include <string>

namespace taebp {
namespace {

template <typename E>
ErrorReport Of(const E& e) {
  return ReportOf(std::make_exception_ptr(e));
}

TEST(ReportOf, EachKindHasItsExitCodeAndLine) {
  struct Case {
    ErrorReport report;
    ErrorKind kind;
    int exit_code;
    std::string line;
  };
  const Case cases[] = {
      {Of(ConfigError("scenario.flow = -1")), ErrorKind::kConfig, 2,
       "taebp: config error: scenario.flow = -1"},
      {Of(persuasion::InvalidArgument("trust 2 is not in [0, 1]")), ErrorKind::kInvalidArgument, 2,
       "taebp: invalid argument: trust 2 is not in [0, 1]"},
      {Of(OutputError("--out x is a file")), ErrorKind::kOutput, 2, "taebp: --out x is a file"},
      {Of(SumoError("SUMO step failed")), ErrorKind::kSumo, 3, "taebp: SUMO step failed"},
      {Of(StallError("junction B1 stalled", "B1", 10, 70)), ErrorKind::kStall, 4,
       "taebp: stalled: junction B1 stalled"},
      {Of(SimulationBusy("a simulation runs")), ErrorKind::kBusy, 1,
       "taebp: error: a simulation runs"},
      {Of(std::runtime_error("disk on fire")), ErrorKind::kOther, 1, "taebp: error: disk on fire"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    EXPECT_EQ(c.report.kind, c.kind);
    EXPECT_EQ(c.report.exit_code, c.exit_code);
    EXPECT_EQ(c.report.line, c.line);
  }
}

TEST(ReportOf, AnInterruptExitsWith128PlusItsSignal) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const ErrorReport r = Of(Interrupted(signal));
    EXPECT_EQ(r.kind, ErrorKind::kInterrupted);
    EXPECT_EQ(r.exit_code, 128 + signal);
    EXPECT_EQ(r.line, "taebp: " + r.message);
    EXPECT_FALSE(r.message.empty());
  }
  EXPECT_EQ(Of(Interrupted(SIGINT)).exit_code, 130);  // Ctrl-C, as the README says
}

TEST(ReportOf, NotAStdExceptionOrNoneIsAnUnknownError) {
  for (const std::exception_ptr& e : {std::make_exception_ptr(42), std::exception_ptr()}) {
    const ErrorReport r = ReportOf(e);
    EXPECT_EQ(r.kind, ErrorKind::kOther);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.line, "taebp: error: unknown error");
  }
}

}  // namespace
}  // namespace taebp
