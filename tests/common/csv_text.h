// CSV text split into lines and cells (the outputs' cells hold no comma):
// for the tests that read encounters.csv, junctions.csv, collisions.csv.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace taebp::test {

inline std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  out.push_back(cell);
  return out;
}

inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace taebp::test
