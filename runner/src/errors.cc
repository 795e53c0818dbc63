#include "taebp/runner/errors.h"

#include "taebp/config/config.h"
#include "taebp/controller/network_controller.h"
#include "taebp/controller/sumo_adapter.h"
#include "taebp/persuasion/persuasion.h"
#include "taebp/rundir/interrupt.h"
#include "taebp/rundir/output_dir.h"
#include "taebp/runner/runner.h"

namespace taebp {

ErrorReport ReportOf(std::exception_ptr error) {
  ErrorReport r;
  auto as = [&r](ErrorKind kind, const char* what) {
    r.kind = kind;
    r.exit_code = ErrorKindOf(kind).exit_code;
    r.message = what;
  };
  try {
    if (error) std::rethrow_exception(error);
    as(ErrorKind::kOther, "unknown error");
  } catch (const ConfigError& e) {
    as(ErrorKind::kConfig, e.what());
  } catch (const persuasion::InvalidArgument& e) {
    as(ErrorKind::kInvalidArgument, e.what());
  } catch (const OutputError& e) {
    as(ErrorKind::kOutput, e.what());
  } catch (const SumoError& e) {
    as(ErrorKind::kSumo, e.what());
  } catch (const StallError& e) {
    as(ErrorKind::kStall, e.what());
  } catch (const SimulationBusy& e) {
    as(ErrorKind::kBusy, e.what());
  } catch (const Interrupted& e) {
    as(ErrorKind::kInterrupted, e.what());
    r.exit_code = e.exit_code();
  } catch (const std::exception& e) {
    as(ErrorKind::kOther, e.what());
  } catch (...) {
    as(ErrorKind::kOther, "unknown error");
  }
  r.line = "taebp: " + std::string(ErrorKindOf(r.kind).prefix) + r.message;
  return r;
}

}  // namespace taebp
