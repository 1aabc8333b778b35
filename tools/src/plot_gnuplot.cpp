#include "plot_gnuplot.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "plot_csv.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {

// Lines one plot draws at most (a 64-joint robot's positions fit).
constexpr std::size_t kMaxPlotSeries = 64;

std::string gnuplotQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

// gnuplot's enhanced text treats _ ^ @ & { } as markup; titles are plain.
std::string gnuplotPlainTitle(const std::string& text) { return gnuplotQuoted(text) + " noenhanced"; }

namespace {

namespace fs = std::filesystem;

struct Series {
  const CsvTable* table;
  std::size_t column;  // 1-based
  std::string title;
  bool steps = false;
  std::string datablock;  // plot this inline data block ("$command0") instead of the file
};

std::string plotCommand(const std::vector<Series>& series) {
  std::string command = "plot ";
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const std::string source = s.datablock.empty() ? gnuplotQuoted(s.table->file.string()) + " skip 1" : s.datablock;
    command += (i == 0 ? "" : ", \\\n     ") + source + " using 1:" +
               std::to_string(s.column) + " with " + (s.steps ? "steps dashtype 2 linewidth 2" : "lines linewidth 2") +
               " title " + gnuplotPlainTitle(s.title);
  }
  return command + "\n";
}

std::string defaultTitle(const std::vector<CsvTable>& tables) {
  std::string names;
  for (const CsvTable& table : tables) names += (names.empty() ? "" : ", ") + table.file.filename().string();
  return "servoloop recording: " + names;
}

// The last time stamp of a recording (its last row's first field).
double lastTime(const CsvTable& table) {
  std::ifstream in(table.file);
  std::string line, last;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last.empty() ? 0.0 : std::stod(last.substr(0, last.find(',')));
}

// A command holds its value until the next one: an inline data block with the
// recording's rows plus its last value repeated at end_time_s, so a command
// published once still draws as a line across the plot.
std::string heldCommandBlock(const CsvTable& table, const std::string& name, double end_time_s) {
  std::ifstream in(table.file);
  std::string block = name + " << EOD\n";
  std::string line, last_value;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    block += line + "\n";
    last_value = line.substr(line.find(',') + 1);
  }
  if (!last_value.empty()) block += std::to_string(end_time_s) + "," + last_value + "\n";
  return block + "EOD\n";
}

bool gnuplotInstalled() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((fs::path(dir) / "gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

}  // namespace

std::string makeGnuplotScript(const PlotRequest& request) {
  if (request.csv_files.empty()) throw Error("nothing to plot: give at least one CSV file");
  std::vector<CsvTable> tables;
  tables.reserve(request.csv_files.size());
  for (const fs::path& file : request.csv_files) tables.push_back(readCsvTable(file));
  for (const CsvTable& table : tables) {
    if (table.rows == 0) throw Error("CSV file '" + table.file.string() + "' has a header but no rows: nothing to plot");
  }

  std::ostringstream script;
  script << "set terminal pngcairo size " << request.width_px << "," << request.height_px
         << " enhanced font 'sans,10'\n"
         << "set output " << gnuplotQuoted(request.png.string()) << "\n"
         << "set datafile separator ','\n"
         << "set grid\nset key outside right top box\n"
         << "set xlabel 'simulated time (s)'\n";
  const std::string title = request.title.empty() ? defaultTitle(tables) : request.title;

  const CsvTable* joint_states = nullptr;
  for (const CsvTable& table : tables) {
    if (table.isJointState()) {
      joint_states = &table;
      break;
    }
  }

  if (!request.columns.empty() || joint_states == nullptr) {
    // One panel: the chosen columns (or every data column) of every file.
    std::vector<Series> series;
    for (const CsvTable& table : tables) {
      for (std::size_t i = 1; i < table.columns.size(); ++i) {
        const std::string& name = table.columns[i];
        bool wanted = request.columns.empty();
        for (const std::string& column : request.columns) wanted |= (column == name);
        if (!wanted) continue;
        const std::string series_title = tables.size() > 1 ? table.file.stem().string() + ": " + name : name;
        requireDrawableColumn(table, i);  // gnuplot skips NaN and inf; a column of nothing but those draws nothing
        series.push_back({&table, i + 1, series_title, table.isFloat64(), ""});
      }
    }
    if (series.size() > kMaxPlotSeries) {
      throw Error("the plot would draw " + std::to_string(series.size()) + " lines; one plot draws at most " +
                  std::to_string(kMaxPlotSeries) + " (a legend of more says nothing): choose some with "
                  "--columns NAME,...");
    }
    if (series.empty()) {
      std::string known;
      for (const CsvTable& table : tables) {
        for (std::size_t i = 1; i < table.columns.size(); ++i) known += (known.empty() ? "" : ", ") + table.columns[i];
      }
      std::string asked;
      for (const std::string& column : request.columns) asked += (asked.empty() ? "" : ",") + column;
      throw Error("--columns " + asked + ": no file has such a column (columns: " + known + ")");
    }
    script << "set title " << gnuplotPlainTitle(title) << "\nset ylabel 'value'\n" << plotCommand(series);
    script << "unset output\n";
    return script.str();
  }

  // Three panels: position (with the commands), velocity, effort. Fixed
  // margins keep the three time axes aligned whatever the legends' widths.
  const std::vector<std::string> joints = joint_states->jointNames();
  double end_time_s = 0.0;
  for (const CsvTable& table : tables) end_time_s = std::max(end_time_s, lastTime(table));
  std::vector<Series> commands;
  std::size_t command_count = 0;
  for (const CsvTable& table : tables) command_count += table.isFloat64() ? 1 : 0;
  for (const CsvTable& table : tables) {
    if (!table.isFloat64()) continue;
    const std::string block = "$command" + std::to_string(commands.size());
    script << heldCommandBlock(table, block, end_time_s);
    const std::string series_title = command_count == 1 ? "command" : "command: " + table.file.stem().string();
    commands.push_back({&table, 2, series_title, true, block});
  }
  struct Panel {
    const char* field;
    const char* label;
  };
  const Panel panels[] = {{"position", "joint position (rad)"},
                          {"velocity", "joint velocity (rad/s)"},
                          {"effort", "joint effort (N·m)"}};
  script << "set lmargin at screen 0.08\nset rmargin at screen 0.80\n";
  script << "set multiplot layout 3,1 title " << gnuplotPlainTitle(title) << "\n";
  for (const Panel& panel : panels) {
    std::vector<Series> series;
    if (joints.size() > kMaxPlotSeries) {
      throw Error("the joint states hold " + std::to_string(joints.size()) + " joints; one plot draws at most " +
                  std::to_string(kMaxPlotSeries) + " lines per panel: choose some with --columns NAME.position,...");
    }
    for (const std::string& joint : joints) {
      const std::string column = joint + "." + panel.field;
      series.push_back({joint_states, joint_states->columnNumber(column), column, false, ""});
    }
    if (std::string(panel.field) == "position") series.insert(series.end(), commands.begin(), commands.end());
    script << "set ylabel " << gnuplotQuoted(panel.label) << "\n" << plotCommand(series);
  }
  script << "unset multiplot\nunset output\n";
  return script.str();
}

void runGnuplotScript(const std::string& script, const fs::path& png) {
  if (!gnuplotInstalled()) {
    throw Error("gnuplot is not installed, so no plot can be drawn; install the Debian package gnuplot-nox "
                "(sudo apt-get install gnuplot-nox)");
  }
  std::error_code error;
  if (png.has_parent_path()) fs::create_directories(png.parent_path(), error);
  fs::remove(png, error);

  char errors_path[] = "/tmp/servoloop-gnuplot-XXXXXX";
  const int errors_fd = ::mkstemp(errors_path);
  if (errors_fd < 0) throw Error("cannot create a temporary file for gnuplot's messages in /tmp");
  ::close(errors_fd);
  // mkstemp's name holds no quote, so single quotes protect it from the shell.
  FILE* pipe = ::popen(("gnuplot 2>'" + std::string(errors_path) + "'").c_str(), "w");
  if (pipe == nullptr) {
    ::unlink(errors_path);
    throw Error("cannot start gnuplot");
  }
  // A gnuplot that dies early must not take this process down with SIGPIPE.
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = ::pclose(pipe);
  ::sigaction(SIGPIPE, &previous, nullptr);

  std::ifstream messages(errors_path);
  std::string first_error;
  for (std::string line; std::getline(messages, line);) {
    if (line.find_first_not_of(" \t^") == std::string::npos) continue;
    if (first_error.empty() || line.find("error") != std::string::npos) {
      first_error = line;
      if (line.find("error") != std::string::npos) break;
    }
  }
  ::unlink(errors_path);
  const bool exited_ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!exited_ok || !fs::exists(png) || fs::file_size(png, error) == 0) {
    throw Error("gnuplot failed to draw '" + png.string() + "'" +
                (first_error.empty() ? std::string() : ": " + first_error));
  }
}

void plotToPng(const PlotRequest& request) {
  if (request.png.empty()) throw Error("no PNG file to plot to: give -o FILE.png");
  runGnuplotScript(makeGnuplotScript(request), request.png);
}

}  // namespace servoloop::cli
