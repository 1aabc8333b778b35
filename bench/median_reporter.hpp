#pragma once
// Medians and ratios for benchmarks run on a noisy, shared machine.
//
// Absolute times on such a machine say more about the neighbours than about
// the code, so every servoloop benchmark is run with repetitions, in random
// interleaved order (Google Benchmark's --benchmark_enable_random_interleaving),
// and compared with its reference *within the same run*: the figures that
// matter are ratios of medians. MedianReporter collects every repetition, shows
// Google Benchmark's console table (aggregates only when repeated), and lets a
// summary print medians, quartile spreads and ratios at the end.
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace servoloop::bench {

// Name of the user counter that says how many units of work (control cycles,
// physics steps) one benchmark iteration does; per-unit times divide by it.
inline constexpr const char* kUnitsPerIterationCounter = "units_per_iteration";

enum class Clock { wall, thread_cpu };

// Quantile q in [0, 1] of values (linear interpolation); NaN when empty.
double quantileOf(std::vector<double> values, double q);

// Per-repetition times of every benchmark, in nanoseconds per unit of work.
class MedianTable {
 public:
  void add(const std::string& name, double wall_ns, double cpu_ns);

  bool has(const std::string& name) const { return samples_.count(name) != 0; }
  std::size_t repetitions(const std::string& name) const;
  // Quantile q in [0, 1] of the per-repetition times (linear interpolation).
  double quantile(const std::string& name, Clock clock, double q) const;
  double median(const std::string& name, Clock clock) const { return quantile(name, clock, 0.5); }
  // (q3 − q1) / median: how much the repetitions spread, relative.
  double relativeSpread(const std::string& name, Clock clock) const;
  // median(numerator) / median(denominator).
  double ratio(const std::string& numerator, const std::string& denominator, Clock clock) const;
  std::vector<std::string> names() const;

 private:
  struct Samples {
    std::vector<double> wall_ns;
    std::vector<double> cpu_ns;
  };
  const std::vector<double>& values(const std::string& name, Clock clock) const;
  std::map<std::string, Samples> samples_;
};

class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override;
  const MedianTable& table() const { return table_; }

 private:
  MedianTable table_;
};

// Runs the registered benchmarks with `default_flags` placed before the
// command line's own (so the command line overrides them), then calls
// `summary` with the collected table. Returns the process exit code.
int runWithSummary(int argc, char** argv, const std::vector<std::string>& default_flags,
                   const std::function<void(const MedianTable&, std::ostream&)>& summary);

// "  <label>  median 123.4 ns  (spread 3.1 %, 21 reps)" for both clocks.
void printMedianLine(std::ostream& out, const MedianTable& table, const std::string& name,
                     const std::string& label);
// "  <label>  1.07 (wall)  1.05 (thread CPU)" and whether it meets `target`
// (ratio <= target; no verdict when target <= 0).
void printRatioLine(std::ostream& out, const MedianTable& table, const std::string& numerator,
                    const std::string& denominator, const std::string& label, double target = 0.0);

}  // namespace servoloop::bench
