"""The exceptions of taebp from Python, each with ``exit_code``: the code the
``taebp`` program exits with for the same error (EXIT_CODES). `import taebp`
names them taebp.ConfigError, ... (their __module__ is the package's)."""

from . import _taebp

ConfigError = _taebp.ConfigError          # bad config, --set or problem (ValueError)
InvalidArgument = _taebp.InvalidArgument  # a parameter out of range (ValueError)
SumoError = _taebp.SumoError              # SUMO failed (RuntimeError)
BusyError = _taebp.SimulationBusy         # a second simulation in this process (RuntimeError)
OutputError = _taebp.OutputError          # an out= folder not usable, a sweep's, in use (OSError)
# A KeyboardInterrupt: Ctrl-C during run() (exit_code 130); SIGTERM or SIGHUP during
# run() or sweep() once Python's own handler for it has returned (143, 129: by
# default that handler ends the process instead). Ctrl-C in sweep() raises a plain
# KeyboardInterrupt.
Interrupted = _taebp.Interrupted
# Every exception's `exit_code`: the code `taebp` exits with for the same error
# (report/exit_codes.h, the README's "Exit codes").
EXIT_CODES = dict(_taebp.exit_codes())


class StallError(RuntimeError):
    """Traffic stalled under scenario.stall_action: error (``taebp run`` exits 4).

    The experiment stopped after the stalled policy; ``result`` is the
    RunResult of the policies that ran, that one included (written to ``out``
    when given), its stall in ``summary["policies"][policy]["stalls"]``."""

    exit_code = EXIT_CODES["StallError"]

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


class SweepError(RuntimeError):
    """A sweep finished with failed (or, after an interrupt, missing) tasks.

    ``result`` is the SweepResult of the tasks that did finish, ``failed`` a
    list of (point, replicate, error) as recorded in the sweep's journal."""

    exit_code = EXIT_CODES["Error"]  # as `taebp sweep` with a failed task

    def __init__(self, message, result, failed):
        super().__init__(message)
        self.result = result
        self.failed = failed
