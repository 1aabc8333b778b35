#pragma once
// Decides, in control time, when something that runs at its own rate
// (publishing joint states at publish_rate, a controller's own update_rate) is
// due. The first check after reset() is due; after that, one check per
// interval. A check counts as due when the control time is within half a
// control period of the next due time, so 50 Hz at a 1 kHz control rate is due
// exactly every 20th cycle despite rounding in the accumulated time.
// Real-time safe.
#include "servoloop/core/time.hpp"

namespace servoloop::controllers {

class PeriodicGate {
 public:
  // rate_hz <= 0: never due.
  explicit PeriodicGate(double rate_hz = 0.0) { setRate(rate_hz); }

  // Non-real-time.
  void setRate(double rate_hz) noexcept {
    rate_hz_ = rate_hz;
    interval_s_ = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  }
  double rate() const noexcept { return rate_hz_; }

  // Real-time: the next check is due (call from starting()).
  void reset() noexcept { first_ = true; }

  // Real-time. time: this cycle's control time; period: the control time
  // since the previous check.
  bool due(const Time& time, const Duration& period) noexcept {
    if (!(rate_hz_ > 0.0)) return false;
    if (first_) {
      first_ = false;
      last_due_ = time;
      return true;
    }
    const double elapsed_s = (time - last_due_).seconds;
    const double tolerance_s = period.seconds > 0.0 ? 0.5 * period.seconds : 0.0;
    if (elapsed_s + tolerance_s < interval_s_) return false;
    // Advance by whole intervals so the average rate stays exact; after a
    // stall of more than one interval, start again from now instead of
    // firing on every cycle to catch up.
    last_due_ = last_due_ + Duration(interval_s_);
    if ((time - last_due_).seconds + tolerance_s >= interval_s_) last_due_ = time;
    return true;
  }

 private:
  double rate_hz_ = 0.0;
  double interval_s_ = 0.0;
  bool first_ = true;
  Time last_due_;
};

}  // namespace servoloop::controllers
