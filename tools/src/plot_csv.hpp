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
  // Per column: the rows whose field is a finite number (NaN, inf and empty
  // fields are not drawn; gnuplot skips them).
  std::vector<std::size_t> finite;
  // Per column: "" or the error naming the file, line and column of its
  // first field that is not a number (a text column, e.g. names).
  std::vector<std::string> not_a_number;

  // What the recording holds, from its header.
  bool isJointState() const;  // time,<joint>.position,<joint>.velocity,<joint>.effort...
  bool isFloat64() const;     // time,data
  // 1-based column number of `name` (gnuplot's numbering), 0 if absent.
  std::size_t columnNumber(const std::string& name) const;
  // The joints of a JointState recording, in column order.
  std::vector<std::string> jointNames() const;
};

// Reads the header and checks every row. Throws servoloop::Error naming the
// file when it is missing, empty, or its first column is not "time", and the
// file, line and column of a row that is not text, has another number of
// fields than the header, or whose time is not a finite number. Other
// fields that are not numbers (empty fields, "nan" and "inf" are numbers
// gnuplot leaves out) are kept in not_a_number for requireDrawableColumn.
CsvTable readCsvTable(const std::filesystem::path& file);

// Throws servoloop::Error when column `index` (0-based) of `table` is to be
// drawn but holds a field that is not a number, or no finite number at all.
void requireDrawableColumn(const CsvTable& table, std::size_t index);

}  // namespace servoloop::cli
