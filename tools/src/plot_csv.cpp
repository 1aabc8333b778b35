#include "plot_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
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

namespace {

// Why `line` (line number `number` of `file`) is not CSV text, or "".
std::string notTextProblem(const std::string& line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if (c == '\t' || (c == '\r' && i + 1 == line.size())) continue;
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", c);
      return "byte " + std::string(hex) + " at column " + std::to_string(i + 1) +
             " is not text (a binary file? a recording of `servoloop launch --record` is a text CSV)";
    }
  }
  return "";
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// A field's number; nullopt when the field is not one. Empty is NaN (missing).
std::optional<double> fieldNumber(const std::string& field) {
  const std::string text = trimmed(field);
  if (text.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::string_view body = lower.front() == '-' || lower.front() == '+' ? std::string_view(lower).substr(1)
                                                                             : std::string_view(lower);
  if (body == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (body == "inf" || body == "infinity") {
    return lower.front() == '-' ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  }
  const char* begin = text.data() + (text.front() == '+' ? 1 : 0);
  double value = 0.0;
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (end != text.data() + text.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) return std::numeric_limits<double>::infinity();
  if (error != std::errc()) return std::nullopt;
  return value;
}

}  // namespace

CsvTable readCsvTable(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("CSV file '" + file.string() + "' cannot be read; check the path");
  CsvTable table;
  table.file = file;
  const auto fail = [&](std::size_t line_number, const std::string& what) {
    throw Error("CSV file '" + file.string() + "', line " + std::to_string(line_number) + ": " + what);
  };
  std::string line;
  if (!std::getline(in, line) || line.empty() || line == "\r") {
    throw Error("CSV file '" + file.string() + "' is empty: the topic carried no message while it was recorded");
  }
  if (const std::string problem = notTextProblem(line); !problem.empty()) fail(1, problem);
  table.columns = splitCommas(line);
  if (table.columns.empty() || table.columns.front() != "time") {
    throw Error("CSV file '" + file.string() +
                "': the first column must be 'time' (a recording of `servoloop launch --record`)");
  }
  table.finite.assign(table.columns.size(), 0);
  table.not_a_number.assign(table.columns.size(), "");
  std::size_t line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    if (const std::string problem = notTextProblem(line); !problem.empty()) fail(line_number, problem);
    // A trailing empty field ("1,") counts: getline drops it, the header's count does not.
    std::vector<std::string> fields = splitCommas(line);
    if (line.back() == ',') fields.emplace_back();  // (",\r" already gave its empty field)
    if (fields.size() != table.columns.size()) {
      fail(line_number, "a row of " + std::to_string(fields.size()) + " field" + (fields.size() == 1 ? "" : "s") +
                            " where the header has " + std::to_string(table.columns.size()) +
                            " (a recording cut off mid-line, or rows of another topic?)");
    }
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::optional<double> value = fieldNumber(fields[i]);
      if (!value) {
        std::string shown = fields[i].size() > 40 ? fields[i].substr(0, 40) + "..." : fields[i];
        const std::string problem = "CSV file '" + file.string() + "', line " + std::to_string(line_number) +
                                    ", column " + std::to_string(i + 1) + " ('" + table.columns[i] + "'): '" + shown +
                                    "' is not a number";
        if (i == 0) throw Error(problem);
        // A text column (names, diagnostics) is an error only when it is to be drawn.
        if (table.not_a_number[i].empty()) table.not_a_number[i] = problem;
        continue;
      }
      if (i == 0 && !std::isfinite(*value)) {
        fail(line_number, "column 1 ('time'): '" + trimmed(fields[i]) + "' is not a finite time; every row needs "
                          "the simulated time it was recorded at");
      }
      if (std::isfinite(*value)) ++table.finite[i];
    }
    ++table.rows;
  }
  return table;
}

void requireDrawableColumn(const CsvTable& table, std::size_t index) {
  if (index < table.not_a_number.size() && !table.not_a_number[index].empty()) {
    throw Error(table.not_a_number[index] + "; gnuplot draws numbers only: leave the column out with --columns");
  }
  if (index >= table.finite.size() || table.finite[index] != 0 || table.rows == 0) return;
  throw Error("CSV file '" + table.file.string() + "': column " + std::to_string(index + 1) + " ('" +
              table.columns[index] + "') holds no finite number in its " + std::to_string(table.rows) +
              " row" + (table.rows == 1 ? "" : "s") +
              " (all NaN, infinite or empty), so there is nothing to draw; leave it out with --columns");
}

}  // namespace servoloop::cli
