#pragma once
// Reading the CSV files `servoloop launch --record` writes (first column
// `time`, a header row, then numbers), for plotting.
#include <filesystem>
#include <string>
#include <vector>

namespace servoloop::cli {

struct CsvTable {
  std::filesystem::path file;
  std::vector<std::string> columns;  // header names, columns[0] is "time"
  std::size_t rows = 0;              // data rows

  // What the recording holds, from its header.
  bool isJointState() const;  // time,<joint>.position,<joint>.velocity,<joint>.effort...
  bool isFloat64() const;     // time,data
  // 1-based column number of `name` (gnuplot's numbering), 0 if absent.
  std::size_t columnNumber(const std::string& name) const;
  // The joints of a JointState recording, in column order.
  std::vector<std::string> jointNames() const;
};

// Reads the header and counts the rows. Throws servoloop::Error naming the
// file when it is missing, empty, or its first column is not "time".
CsvTable readCsvTable(const std::filesystem::path& file);

}  // namespace servoloop::cli
