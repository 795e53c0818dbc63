// Fuzz target: the `taebp solve` problem loader (LoadProblemConfig), reading
// the input as the problem file. Errors must be ConfigError.
#include "fuzz_support.h"
#include "taebp/config/config.h"

#include <sys/mman.h>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const int fd = ::memfd_create("problem.yaml", 0);
  static const std::string path = "/proc/self/fd/" + std::to_string(fd);
  if (fd < 0 || ::ftruncate(fd, 0) != 0 || ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size))
    taebp::fuzz::Finding("cannot write the memfd");
  try {
    const taebp::ProblemConfig p = taebp::LoadProblemConfig(path);
    (void)p;
  } catch (const taebp::ConfigError&) {
  }
  return 0;
}
