// The error every layer may raise about its input: a configuration error.
// Its message names the file (or --set), the key and the offending value.
// Which exit code and stderr prefix it gets: exit_codes.h (ErrorKind::kConfig),
// runner/errors.h (ErrorKindOf).
#pragma once

#include <stdexcept>

namespace taebp {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace taebp
