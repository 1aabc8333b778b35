#pragma once
// The progress bar of a `servoloop launch --duration` run, on standard error,
// redrawn in place. It draws only when standard error is a terminal, so logs,
// pipes and CI output never see it.
#include <string>

namespace servoloop::cli {

class ProgressBar {
 public:
  // total_s: simulated seconds the run will take.
  explicit ProgressBar(double total_s);
  ~ProgressBar();

  // False when stderr is not a terminal: update/finish then do nothing.
  bool enabled() const { return enabled_; }

  // Redraws: "[#######.............]  12.3 / 30.0 s simulated  (RTF 41.2)".
  void update(double sim_time_s, double wall_time_s);
  // Clears the bar's line. Idempotent.
  void finish();

  // The bar's text for a given state (no terminal control codes); public for tests.
  static std::string render(double sim_time_s, double total_s, double wall_time_s, int width);

 private:
  double total_s_;
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace servoloop::cli
