#pragma once
// PID with the semantics of ROS 1 control_toolbox::Pid, which ros_control's
// effort controllers use; see ros_control_semantics.md "control_toolbox PID".
//
//   command = P + I + D
//   P = p·e
//   i_error += dt·e;  with antiwindup (and i ≠ 0) i_error is kept inside
//                     [min(i_min/i, i_max/i), max(i_min/i, i_max/i)]
//   I = i·i_error;    without antiwindup I is clamped to [i_min, i_max] while
//                     i_error keeps growing
//   D = d·ė
//
// With i_max = i_min = 0 (no i_clamp given) there is no integral action at all,
// as in control_toolbox.
//
// Threads: computeCommand, reset, getCurrentPIDErrors, getCurrentCmd and
// getActiveGains belong to the one thread that runs the controller (the
// real-time thread); they never allocate, lock or throw. setGains, getGains and
// initFromParams may be called from any other thread at any time: the gains
// travel through a sequence lock, and computeCommand picks up a new set at its
// next call (if a set is being written at that very moment, it keeps the
// previous gains for one more cycle instead of waiting).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <string>

#include "servoloop/params/parameters.hpp"

namespace servoloop::controllers {

class Pid {
 public:
  struct Gains {
    double p_gain = 0.0;
    double i_gain = 0.0;
    double d_gain = 0.0;
    double i_max = 0.0;  // upper bound of the integral term I (or of i·i_error with antiwindup)
    double i_min = 0.0;  // lower bound of the same
    bool antiwindup = false;
  };

  explicit Pid(double p = 0.0, double i = 0.0, double d = 0.0, double i_max = 0.0,
               double i_min = 0.0, bool antiwindup = false);
  // Copies gains and state. Non-real-time; other may not be written concurrently.
  Pid(const Pid& other);
  Pid& operator=(const Pid& other);

  // Non-real-time. Sets the gains and resets the state.
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);

  // Non-real-time. pid_node: the controller's `pid` map, e.g.
  //   pid: {p: 10.0, i: 10.0, d: 10.0, i_clamp_min: -10.0, i_clamp_max: 10.0}
  // where: its location, named in errors, e.g. "one_DOF_robot/joint1_position_controller/pid".
  // Keys: p (required), i, d (default 0); i_clamp sets i_max = |c|, i_min = -|c|;
  // i_clamp_min then sets i_min = -|value| and i_clamp_max sets i_max = |value|;
  // antiwindup (default false). Unknown keys are ignored, as control_toolbox does.
  // Sets the gains and resets the state. Throws servoloop::ConfigError
  // "<where>: No p gain specified for pid ..." when p is missing, and one naming
  // <where>/<key> and the expected type when a value has the wrong type.
  void initFromParams(const params::Parameters& pid_params, const std::string& where);

  // Any thread. Calls from several threads are serialised; never blocks
  // computeCommand.
  void setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);
  void setGains(const Gains& gains);

  // Any thread: the last gains set. Lock-free; retries only while a setGains
  // is writing (a few stores). On the controller's own thread prefer
  // getActiveGains(), which never retries.
  Gains getGains() const;
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min) const;
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min,
                bool& antiwindup) const;

  // Controller thread: the gains the last computeCommand used (before the first
  // one, the gains at construction, initPid or initFromParams).
  const Gains& getActiveGains() const noexcept { return active_gains_; }

  // Controller thread. Zeroes the integral, the errors and the command; the
  // previous error counts as 0, so the first computeCommand(e, dt) after a
  // reset sees ė = e/dt (the derivative "kick" control_toolbox has).
  void reset() noexcept;

  // Controller thread. ė = (e - e_previous)/dt; returns 0 and changes nothing
  // when dt is 0 or not finite, or e is not finite. With dt < 0 the previous
  // ė is reused (as control_toolbox does).
  double computeCommand(double error, double dt) noexcept;

  // Controller thread. With a known error derivative (e.g. v_cmd - v). Returns
  // 0 and changes nothing when dt is 0 or not finite, or e or ė is not finite.
  double computeCommand(double error, double error_dot, double dt) noexcept;

  // Controller thread. The errors of the last computeCommand: proportional,
  // integral (i_error) and derivative.
  void getCurrentPIDErrors(double& p_error, double& i_error, double& d_error) const noexcept;

  // Controller thread. The last command computeCommand returned (0 after reset).
  double getCurrentCmd() const noexcept { return command_; }

 private:
  // One attempt at reading the shared gains; false when a write was in progress.
  bool tryReadGains(Gains& gains) const noexcept;

  // The every-cycle part of computeCommand, its inputs checked.
  double computeFiniteCommand(double error, double error_dot, double dt) noexcept;

  // Controller-thread state, first: what every computeCommand reads and
  // writes, on two cache lines.
  // Gains shared with other threads: written under gains_write_mutex_ with an
  // odd sequence number while the write is in progress (a sequence lock).
  std::atomic<std::uint64_t> gains_sequence_{0};
  // The sequence active_gains_ were read at (odd: none yet, as no writer
  // leaves an odd one behind), so the shared gains are only read after a change.
  std::uint64_t active_sequence_ = ~std::uint64_t{0};
  Gains active_gains_;
  double p_error_last_ = 0.0;  // error of the previous computeCommand(e, dt)
  double p_error_ = 0.0;
  double i_error_ = 0.0;
  double d_error_ = 0.0;
  double command_ = 0.0;

  // The shared gains (see gains_sequence_).
  std::atomic<double> shared_p_gain_{0.0};
  std::atomic<double> shared_i_gain_{0.0};
  std::atomic<double> shared_d_gain_{0.0};
  std::atomic<double> shared_i_max_{0.0};
  std::atomic<double> shared_i_min_{0.0};
  std::atomic<bool> shared_antiwindup_{false};
  std::mutex gains_write_mutex_;  // serialises writers; computeCommand never takes it
};

// The controller-thread computation, inline: it runs in every controller
// cycle, so it is compiled into the controllers rather than called across
// libraries.
inline double Pid::computeCommand(double error, double dt) noexcept {
  if (dt == 0.0 || !std::isfinite(dt) || !std::isfinite(error)) return 0.0;

  double error_dot = d_error_;
  if (dt > 0.0) {
    error_dot = (error - p_error_last_) / dt;
    p_error_last_ = error;
  }
  if (!std::isfinite(error_dot)) return 0.0;
  return computeFiniteCommand(error, error_dot, dt);
}

inline double Pid::computeCommand(double error, double error_dot, double dt) noexcept {
  if (dt == 0.0 || !std::isfinite(dt) || !std::isfinite(error) || !std::isfinite(error_dot)) {
    return 0.0;
  }
  return computeFiniteCommand(error, error_dot, dt);
}

inline double Pid::computeFiniteCommand(double error, double error_dot, double dt) noexcept {
  // New gains take effect here; a write in progress leaves the previous ones
  // (and they are read again next time).
  const std::uint64_t sequence = gains_sequence_.load(std::memory_order_acquire);
  if (sequence != active_sequence_ && tryReadGains(active_gains_)) active_sequence_ = sequence;
  const Gains& gains = active_gains_;

  p_error_ = error;
  d_error_ = error_dot;

  const double p_term = gains.p_gain * p_error_;

  i_error_ += dt * p_error_;
  if (gains.antiwindup && gains.i_gain != 0.0) {
    // Keep i_error where i·i_error stays inside [i_min, i_max]; the bounds swap
    // when the integral gain is negative.
    const double bound_a = gains.i_min / gains.i_gain;
    const double bound_b = gains.i_max / gains.i_gain;
    i_error_ = std::clamp(i_error_, std::min(bound_a, bound_b), std::max(bound_a, bound_b));
  }
  double i_term = gains.i_gain * i_error_;
  if (!gains.antiwindup) {
    // Limit the term, not the state: i_error keeps integrating.
    i_term = std::min(std::max(i_term, gains.i_min), gains.i_max);
  }

  const double d_term = gains.d_gain * d_error_;

  command_ = p_term + i_term + d_term;
  return command_;
}

}  // namespace servoloop::controllers
