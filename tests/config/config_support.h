// What the config loader's tests share: the shipped configs' paths and the
// message of a ConfigError a load gives.
#pragma once

#include "taebp/config/config.h"

#include "test_support.h"

#include <string>
#include <utility>
#include <vector>

namespace taebp {
namespace test {

inline const std::string kPaper = std::string(TAEBP_SOURCE_DIR) + "/configs/paper.yaml";
inline const std::string kProblems = std::string(TAEBP_SOURCE_DIR) + "/configs/problems";

// The ConfigError message of `f()`, or a recorded failure.
template <typename F>
std::string ConfigErrorOf(F&& f) {
  return ErrorOf<ConfigError>(std::forward<F>(f));
}

// Loads `yaml` from a file named `name` in a fresh temporary directory; returns
// the ConfigError message and the file's path.
struct FileError {
  std::string message, path;
};
inline FileError LoadError(const std::string& yaml, const std::vector<std::string>& overrides = {},
                           const std::string& name = "exp.yaml") {
  TempDir dir;
  const std::string path = dir.Write(name, yaml);
  return {ConfigErrorOf([&] { LoadExperimentConfig(path, overrides); }), path};
}

}  // namespace test
}  // namespace taebp
