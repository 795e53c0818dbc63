// `taebp sweep` and `taebp merge`: registered on the CLI11 app by main.cc.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace taebp::sweep {

// What `taebp run CONFIG --set ... --out DIR --quiet` does, as a function
// returning its exit code; it reports its own errors on stderr as `taebp run`
// does (an exception escaping it counts as exit code 1).
using RunFunction = std::function<int(const std::string& config,
                                      const std::vector<std::string>& overrides,
                                      const std::string& out_dir)>;

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
