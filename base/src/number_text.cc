#include "taebp/base/number_text.h"

#include <charconv>
#include <cstdio>

namespace taebp {

std::string NumberText(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string NumberText(double v, int significant) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof buffer, "%.*g", significant, v);
  return std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
}

}  // namespace taebp
