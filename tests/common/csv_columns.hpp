#pragma once
// A CSV file (as `servoloop launch --record` writes it) read as columns of
// numbers by header name; cells that are not numbers (joint names) read as NaN.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace servoloop::testing {

inline std::map<std::string, std::vector<double>> readCsvColumns(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream header_stream(line);
  for (std::string cell; std::getline(header_stream, cell, ',');) header.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t i = 0;
    for (std::string cell; std::getline(row, cell, ',') && i < header.size(); ++i) {
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      columns[header[i]].push_back(end != cell.c_str() ? value : NAN);
    }
  }
  return columns;
}

}  // namespace servoloop::testing
