// CSV files of the outputs as rows of named cells, for tests that read what a
// run or a sweep wrote (cells split as report.h SplitCsvRow writes them: a
// quoted cell keeps its quotes).
#pragma once

#include "test_support.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace taebp::test {

inline std::vector<std::string> SplitQuotedCsvLine(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) {
      cells.emplace_back();
      continue;
    }
    cells.back() += c;
  }
  return cells;
}

// Each row of a CSV file as {column: cell}.
inline std::vector<std::map<std::string, std::string>> ReadCsvRows(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::string line;
  std::vector<std::map<std::string, std::string>> rows;
  if (!std::getline(f, line)) return rows;
  const std::vector<std::string> header = SplitQuotedCsvLine(line);
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = SplitQuotedCsvLine(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace taebp::test
