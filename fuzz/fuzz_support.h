// Shared by the fuzz targets: splitting an input into its parts.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace taebp::fuzz {

// The input split at the first line that is exactly `marker` (the marker line
// itself dropped); the second part is empty when there is no such line.
inline std::pair<std::string, std::string> SplitAt(const std::string& text,
                                                   const std::string& marker) {
  const std::string line = "\n" + marker + "\n";
  if (text.rfind(marker + "\n", 0) == 0) return {"", text.substr(marker.size() + 1)};
  const auto at = text.find(line);
  if (at == std::string::npos) return {text, ""};
  return {text.substr(0, at + 1), text.substr(at + line.size())};
}

// Non-empty lines.
inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

inline void ReplaceAll(std::string* s, const std::string& from, const std::string& to) {
  for (std::size_t at = s->find(from); at != std::string::npos; at = s->find(from, at + to.size()))
    s->replace(at, from.size(), to);
}

// An invariant broke: report and abort (libFuzzer saves the input).
[[noreturn]] inline void Finding(const std::string& what) {
  std::fprintf(stderr, "taebp fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace taebp::fuzz
