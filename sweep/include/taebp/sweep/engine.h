// The sweep engine: runs a config's sweep (grid point x seed replicate
// tasks, each a `run` of every policy in its own process: forked workers,
// MPI ranks or Slurm-array shards) with a crash-safe journal, and merges
// shard directories. `taebp sweep` / `taebp merge` (cli/) only parse
// the command line into these options.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace taebp::sweep {

// What `taebp run CONFIG --set ... --out DIR --quiet` does, as a function
// returning its exit code; it reports its own errors on stderr as `taebp run`
// does (an exception escaping it counts as exit code 1).
using RunFunction = std::function<int(const std::string& config,
                                      const std::vector<std::string>& overrides,
                                      const std::string& out_dir)>;

struct SweepOptions {
  std::string config, out, shard;
  std::vector<std::string> overrides;
  int jobs = 0;
  bool quiet = false, list = false, mpi = false, exec = false;
  bool reuse = true;  // false (--no-reuse): run every policy at every point
};

struct MergeOptions {
  std::string out;
  std::vector<std::string> dirs;
  bool quiet = false;
};

// Runs (or with `list`, prints) the sweep. With `run`, each task is a fork of
// this process that calls it (no exec: the libraries are already loaded);
// without it, with `exec`, or under MPI, a task execs `/proc/self/exe run ...`.
// Returns the exit code (0 all ok, 1 a task failed, 130 interrupted); throws
// ConfigError for a bad config or option.
int RunSweep(const SweepOptions& options, const RunFunction& run);

// True when the engine was built with MPI (mpirun -np K taebp sweep ...).
bool HaveMpi();

// Joins shard directories into options.out; returns the exit code.
int RunMerge(const MergeOptions& options);

}  // namespace taebp::sweep
