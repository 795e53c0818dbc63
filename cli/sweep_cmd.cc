// `taebp sweep` and `taebp merge`: command-line parsing only; the engine is
// sweep/ (taebp/sweep/engine.h).
#include "sweep_cmd.h"

#include <CLI/CLI.hpp>

#include <utility>

namespace taebp::sweep {

struct Commands::Impl {
  RunFunction run;
  SweepOptions sweep;
  MergeOptions merge;
  CLI::App* sweep_cmd = nullptr;
  CLI::App* merge_cmd = nullptr;
};

Commands::Commands(CLI::App& app, RunFunction run) : impl_(std::make_unique<Impl>()) {
  impl_->run = std::move(run);
  SweepOptions& s = impl_->sweep;
  CLI::App* sw = app.add_subcommand(
      "sweep",
      "Run an experiment config's sweep: (grid point x seed replicate) tasks, each a `run` of "
      "every policy in its own process; resumable (journal.jsonl), tables in --out");
  sw->add_option("CONFIG", s.config, "experiment YAML with a sweep: section")->required();
  sw->add_option("--set", s.overrides,
                 "override a config key for every task, KEY=VALUE with VALUE read as YAML "
                 "(repeatable), e.g. --set scenario.duration=300 --set sweep.replicates=2")
      ->allow_extra_args(false);  // one value per --set: CONFIG may follow
  sw->add_option("--out", s.out, "output directory (default: results/<config name>)");
  sw->add_option("--jobs,-j", s.jobs,
                 "worker processes at once, >= 1 (default: the number of cores; 1 per MPI rank)")
      ->check(CLI::PositiveNumber);
  sw->add_option("--shard", s.shard,
                 "I/N: run only the tasks whose index % N == I (for Slurm arrays; join with "
                 "`taebp merge`)");
  sw->add_flag("--list", s.list, "print the tasks and exit");
  sw->add_flag("--quiet", s.quiet, "no progress on stderr");
  sw->add_flag_callback("--no-reuse", [&s] { s.reuse = false; },
               "run every policy at every point, also where an earlier run cannot differ "
               "(measuring or checking the reuse; the tables are the same but reused_from)")
      ->group("");  // hidden: for tests and benchmarks
  sw->add_flag("--exec-workers", s.exec,
               "start each task by exec'ing `taebp run` instead of forking (as under MPI)")
      ->group("");  // hidden: for debugging and benchmarks
  if (HaveMpi())
    sw->add_flag("--mpi", s.mpi,
               "use MPI (MPI_Init) even if no MPI launcher is detected; under mpirun/srun it is "
               "automatic: tasks spread over the ranks, rank 0 writes");
  impl_->sweep_cmd = sw;

  MergeOptions& m = impl_->merge;
  CLI::App* mg = app.add_subcommand(
      "merge", "Join the output directories of sweep shards (--shard I/N) into OUT's tables");
  mg->add_option("OUT", m.out, "output directory for the merged tables")->required();
  mg->add_option("SHARD_DIR", m.dirs, "the shards' --out directories")->required();
  mg->add_flag("--quiet", m.quiet, "no summary on stderr");
  impl_->merge_cmd = mg;
}

Commands::~Commands() = default;

bool Commands::Parsed() const { return impl_->sweep_cmd->parsed() || impl_->merge_cmd->parsed(); }

int Commands::Run() {
  if (impl_->sweep_cmd->parsed()) return RunSweep(impl_->sweep, impl_->run);
  return RunMerge(impl_->merge);
}

}  // namespace taebp::sweep
