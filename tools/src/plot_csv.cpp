#include "plot_csv.hpp"

#include <fstream>
#include <sstream>

#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

constexpr std::string_view kPositionSuffix = ".position";

std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) {
    if (!field.empty() && field.back() == '\r') field.pop_back();
    fields.push_back(field);
  }
  return fields;
}

}  // namespace

bool CsvTable::isJointState() const {
  if (columns.size() < 4 || (columns.size() - 1) % 3 != 0) return false;
  for (std::size_t i = 1; i < columns.size(); i += 3) {
    if (!columns[i].ends_with(kPositionSuffix)) return false;
  }
  return true;
}

bool CsvTable::isFloat64() const { return columns.size() == 2 && columns[1] == "data"; }

std::size_t CsvTable::columnNumber(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i + 1;
  }
  return 0;
}

std::vector<std::string> CsvTable::jointNames() const {
  std::vector<std::string> names;
  if (!isJointState()) return names;
  for (std::size_t i = 1; i < columns.size(); i += 3) {
    names.push_back(columns[i].substr(0, columns[i].size() - kPositionSuffix.size()));
  }
  return names;
}

CsvTable readCsvTable(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("CSV file '" + file.string() + "' cannot be read; check the path");
  CsvTable table;
  table.file = file;
  std::string line;
  if (!std::getline(in, line) || line.empty()) {
    throw Error("CSV file '" + file.string() + "' is empty: the topic carried no message while it was recorded");
  }
  table.columns = splitCommas(line);
  if (table.columns.empty() || table.columns.front() != "time") {
    throw Error("CSV file '" + file.string() +
                "': the first column must be 'time' (a recording of `servoloop launch --record`)");
  }
  while (std::getline(in, line)) {
    if (!line.empty()) ++table.rows;
  }
  return table;
}

}  // namespace servoloop::cli
