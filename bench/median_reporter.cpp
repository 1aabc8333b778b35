#include "median_reporter.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace servoloop::bench {

void MedianTable::add(const std::string& name, double wall_ns, double cpu_ns) {
  Samples& samples = samples_[name];
  samples.wall_ns.push_back(wall_ns);
  samples.cpu_ns.push_back(cpu_ns);
}

std::size_t MedianTable::repetitions(const std::string& name) const {
  auto it = samples_.find(name);
  return it == samples_.end() ? 0 : it->second.wall_ns.size();
}

const std::vector<double>& MedianTable::values(const std::string& name, Clock clock) const {
  auto it = samples_.find(name);
  if (it == samples_.end()) throw std::out_of_range("no benchmark named '" + name + "' was run");
  return clock == Clock::wall ? it->second.wall_ns : it->second.cpu_ns;
}

double quantileOf(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double position = q * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return values[below] + fraction * (values[above] - values[below]);
}

double MedianTable::quantile(const std::string& name, Clock clock, double q) const {
  return quantileOf(values(name, clock), q);
}

double MedianTable::relativeSpread(const std::string& name, Clock clock) const {
  return (quantile(name, clock, 0.75) - quantile(name, clock, 0.25)) / median(name, clock);
}

double MedianTable::ratio(const std::string& numerator, const std::string& denominator, Clock clock) const {
  return median(numerator, clock) / median(denominator, clock);
}

namespace {

// "a/joints:8" before "a/joints:16": digit runs compare as numbers.
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i_end = i, j_end = j;
      while (i_end < a.size() && std::isdigit(static_cast<unsigned char>(a[i_end]))) ++i_end;
      while (j_end < b.size() && std::isdigit(static_cast<unsigned char>(b[j_end]))) ++j_end;
      const unsigned long long x = std::stoull(a.substr(i, i_end - i));
      const unsigned long long y = std::stoull(b.substr(j, j_end - j));
      if (x != y) return x < y;
      i = i_end;
      j = j_end;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

std::vector<std::string> MedianTable::names() const {
  std::vector<std::string> names;
  for (const auto& [name, samples] : samples_) names.push_back(name);
  std::sort(names.begin(), names.end(), naturalLess);
  return names;
}

void MedianReporter::ReportRuns(const std::vector<Run>& runs) {
  std::vector<Run> shown;
  for (const Run& run : runs) {
    if (run.run_type == Run::RT_Aggregate) {
      shown.push_back(run);
      continue;
    }
    if (run.repetitions <= 1) shown.push_back(run);  // no aggregates will follow
    if (run.error_occurred || run.iterations == 0) continue;
    double units = 1.0;
    if (auto counter = run.counters.find(kUnitsPerIterationCounter); counter != run.counters.end()) {
      units = counter->second.value;
    }
    const double per_unit = 1e9 / (static_cast<double>(run.iterations) * units);
    std::string name = run.run_name.function_name;
    if (!run.run_name.args.empty()) name += "/" + run.run_name.args;
    table_.add(name, run.real_accumulated_time * per_unit, run.cpu_accumulated_time * per_unit);
  }
  if (!shown.empty()) ConsoleReporter::ReportRuns(shown);
}

int runWithSummary(int argc, char** argv, const std::vector<std::string>& default_flags,
                   const std::function<void(const MedianTable&, std::ostream&)>& summary) {
  std::vector<std::string> arguments{argv[0]};
  arguments.insert(arguments.end(), default_flags.begin(), default_flags.end());
  for (int i = 1; i < argc; ++i) arguments.emplace_back(argv[i]);
  std::vector<char*> pointers;
  for (std::string& argument : arguments) pointers.push_back(argument.data());
  int count = static_cast<int>(pointers.size());
  benchmark::Initialize(&count, pointers.data());
  if (benchmark::ReportUnrecognizedArguments(count, pointers.data())) return 1;

  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  std::cout << "\n";
  try {
    summary(reporter.table(), std::cout);
  } catch (const std::out_of_range& e) {
    // A --benchmark_filter left out a benchmark the summary compares.
    std::cout << "(summary incomplete: " << e.what() << ")\n";
  }
  std::cout.flush();
  return 0;
}

void printMedianLine(std::ostream& out, const MedianTable& table, const std::string& name,
                     const std::string& label) {
  char line[256];
  std::snprintf(line, sizeof line, "  %-44s %10.1f ns wall (spread %4.1f %%)  %10.1f ns thread CPU  [%zu reps]\n",
                label.c_str(), table.median(name, Clock::wall), 100.0 * table.relativeSpread(name, Clock::wall),
                table.median(name, Clock::thread_cpu), table.repetitions(name));
  out << line;
}

void printRatioLine(std::ostream& out, const MedianTable& table, const std::string& numerator,
                    const std::string& denominator, const std::string& label, double target) {
  const double wall = table.ratio(numerator, denominator, Clock::wall);
  const double cpu = table.ratio(numerator, denominator, Clock::thread_cpu);
  char line[256];
  std::snprintf(line, sizeof line, "  %-44s %6.3f wall   %6.3f thread CPU", label.c_str(), wall, cpu);
  out << line;
  if (target > 0.0) {
    out << "   target <= " << target << ": " << (std::max(wall, cpu) <= target   ? "met"
                                                 : std::min(wall, cpu) <= target ? "met on one clock only"
                                                                                  : "NOT met");
  }
  out << "\n";
}

}  // namespace servoloop::bench
