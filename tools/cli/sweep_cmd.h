// `taebp sweep` and `taebp merge`: registered on the CLI11 app by main.cc.
#pragma once

#include <memory>

namespace CLI {
class App;
}

namespace taebp::sweep {

class Commands {
 public:
  explicit Commands(CLI::App& app);  // adds the `sweep` and `merge` subcommands
  ~Commands();
  bool Parsed() const;  // one of them was given on the command line
  // Runs it; returns the exit code. Throws ConfigError for a bad config.
  int Run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace taebp::sweep
