// `taebp sweep` and `taebp merge`: registered on the CLI11 app by main.cc.
#pragma once

#include "taebp/sweep/engine.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace taebp::sweep {

class Commands {
 public:
  // Adds the `sweep` and `merge` subcommands. With `run`, each task is a
  // fork of this process that calls it (no exec: the libraries are already
  // loaded); without it, or under MPI, a task execs `/proc/self/exe run ...`.
  explicit Commands(CLI::App& app, RunFunction run = {});
  ~Commands();
  bool Parsed() const;  // one of them was given on the command line
  // Runs it; returns the exit code. Throws ConfigError for a bad config.
  int Run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace taebp::sweep
