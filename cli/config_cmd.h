// `taebp config --reference [--format md|json]`: every config key with its
// type, default, allowed values and meaning (config/reference.h), the source
// of docs/reference/config.md. Registered on the CLI11 app by main.cc.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace taebp::cli {

class ConfigCommand {
 public:
  explicit ConfigCommand(CLI::App& app);
  bool Parsed() const;  // `config` was given on the command line
  int Run() const;      // prints; returns the exit code

 private:
  CLI::App* command_;
  bool reference_ = false;
  std::string format_ = "md";
};

}  // namespace taebp::cli
