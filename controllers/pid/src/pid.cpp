#include "servoloop/controllers/pid.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <thread>
#include <type_traits>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/params/schema.hpp"

namespace servoloop::controllers {
namespace {

// The keys control_toolbox's Pid reads (plus publish_state, which its
// controllers read beside them).
const params::Schema& pidGainsSchema() {
  static const params::Schema schema(
      "PID gains",
      {
          {"p", params::ValueType::number, "proportional gain (required; checked by the reader)"},
          {"i", params::ValueType::number, "integral gain"},
          {"d", params::ValueType::number, "derivative gain"},
          {"i_clamp", params::ValueType::number, "integral clamp, both signs (|value| is used)"},
          {"i_clamp_min", params::ValueType::number, "lower integral clamp (forced <= 0)"},
          {"i_clamp_max", params::ValueType::number, "upper integral clamp (forced >= 0)"},
          {"antiwindup", params::ValueType::boolean, "clamp the integral term rather than the error sum"},
          {"publish_state", params::ValueType::boolean, "publish the PID's state (read by the controllers)"},
      },
      params::UnknownKeys::warn);
  return schema;
}

}  // namespace

Pid::Pid(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  initPid(p, i, d, i_max, i_min, antiwindup);
}

Pid::Pid(const Pid& other) : active_gains_(other.active_gains_) {
  setGains(other.getGains());
  p_error_last_ = other.p_error_last_;
  p_error_ = other.p_error_;
  i_error_ = other.i_error_;
  d_error_ = other.d_error_;
  command_ = other.command_;
}

Pid& Pid::operator=(const Pid& other) {
  if (this == &other) return *this;
  setGains(other.getGains());
  active_gains_ = other.active_gains_;
  p_error_last_ = other.p_error_last_;
  p_error_ = other.p_error_;
  i_error_ = other.i_error_;
  d_error_ = other.d_error_;
  command_ = other.command_;
  return *this;
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  const Gains gains{p, i, d, i_max, i_min, antiwindup};
  setGains(gains);
  active_gains_ = gains;
  reset();
}

void Pid::initFromParams(const params::Parameters& pid_params, const std::string& where) {
  const params::Schema& schema = pidGainsSchema();
  const params::Parameters& node = pid_params;
  // The map, types and unknown keys (one warning each: the gain meant stays 0,
  // as ros_control has it).
  schema.check(node);
  if (!node.has("p")) {
    throw ConfigError(where + ": No p gain specified for pid; add p: <gain> under " + where);
  }

  Gains gains;
  gains.p_gain = schema.number(node, "p");
  gains.i_gain = schema.number(node, "i");
  gains.d_gain = schema.number(node, "d");
  if (node.has("i_clamp")) {
    const double clamp = schema.number(node, "i_clamp");
    gains.i_max = std::abs(clamp);
    gains.i_min = -std::abs(clamp);
  }
  // The one-sided keys win over i_clamp, and their signs are forced so that
  // i_min <= 0 <= i_max whatever was written.
  // A sign written the other way round is one warning, as the value used is
  // not the value written.
  const auto forceSign = [&](const char* key, double& value, double sign) {
    if (!node.has(key)) return;
    value = schema.number(node, key);
    const double forced = sign * std::abs(value);
    if (forced != value) {
      logger().warn("{}/{}: {} is used as {} (ros_control forces i_clamp_min <= 0 <= i_clamp_max)", where, key, value,
                    forced);
    }
    value = forced;
  };
  forceSign("i_clamp_min", gains.i_min, -1.0);
  forceSign("i_clamp_max", gains.i_max, 1.0);
  gains.antiwindup = schema.boolean(node, "antiwindup");

  const std::pair<const char*, double> signed_gains[] = {{"p", gains.p_gain}, {"i", gains.i_gain}, {"d", gains.d_gain}};
  for (const auto& [key, gain] : signed_gains) {
    if (gain < 0.0) {
      logger().warn("{}/{}: the gain {} is negative, so the controller pushes away from its set point; ros_control "
                    "allows it, but a stable loop needs gains >= 0 for a joint of positive inertia",
                    where, key, gain);
    }
  }

  initPid(gains.p_gain, gains.i_gain, gains.d_gain, gains.i_max, gains.i_min, gains.antiwindup);
}

void Pid::setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup) {
  setGains(Gains{p, i, d, i_max, i_min, antiwindup});
}

void Pid::setGains(const Gains& gains) {
  std::lock_guard<std::mutex> lock(gains_write_mutex_);
  // Odd sequence: a write is in progress; readers that saw it, or saw the
  // number change, discard what they read. The fields are stored with
  // release and loaded with acquire (rather than fenced, which
  // ThreadSanitizer does not model): a reader that loads a new value also
  // sees the odd sequence before it, so its second look at the sequence
  // finds it changed.
  const std::uint64_t sequence = gains_sequence_.load(std::memory_order_relaxed);
  gains_sequence_.store(sequence + 1, std::memory_order_relaxed);
  shared_p_gain_.store(gains.p_gain, std::memory_order_release);
  shared_i_gain_.store(gains.i_gain, std::memory_order_release);
  shared_d_gain_.store(gains.d_gain, std::memory_order_release);
  shared_i_max_.store(gains.i_max, std::memory_order_release);
  shared_i_min_.store(gains.i_min, std::memory_order_release);
  shared_antiwindup_.store(gains.antiwindup, std::memory_order_release);
  gains_sequence_.store(sequence + 2, std::memory_order_release);
}

bool Pid::tryReadGains(Gains& gains) const noexcept {
  const std::uint64_t before = gains_sequence_.load(std::memory_order_acquire);
  if (before & 1U) return false;
  Gains read;
  read.p_gain = shared_p_gain_.load(std::memory_order_acquire);
  read.i_gain = shared_i_gain_.load(std::memory_order_acquire);
  read.d_gain = shared_d_gain_.load(std::memory_order_acquire);
  read.i_max = shared_i_max_.load(std::memory_order_acquire);
  read.i_min = shared_i_min_.load(std::memory_order_acquire);
  read.antiwindup = shared_antiwindup_.load(std::memory_order_acquire);
  if (gains_sequence_.load(std::memory_order_relaxed) != before) return false;
  gains = read;
  return true;
}

Pid::Gains Pid::getGains() const {
  Gains gains;
  // A writer holds the odd sequence for a few stores; if it was preempted
  // mid-write, let it run rather than spin.
  while (!tryReadGains(gains)) std::this_thread::yield();
  return gains;
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min) const {
  bool antiwindup = false;
  getGains(p, i, d, i_max, i_min, antiwindup);
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min,
                   bool& antiwindup) const {
  const Gains gains = getGains();
  p = gains.p_gain;
  i = gains.i_gain;
  d = gains.d_gain;
  i_max = gains.i_max;
  i_min = gains.i_min;
  antiwindup = gains.antiwindup;
}

void Pid::reset() noexcept {
  p_error_last_ = 0.0;
  p_error_ = 0.0;
  i_error_ = 0.0;
  d_error_ = 0.0;
  command_ = 0.0;
}

void Pid::getCurrentPIDErrors(double& p_error, double& i_error, double& d_error) const noexcept {
  p_error = p_error_;
  i_error = i_error_;
  d_error = d_error_;
}

}  // namespace servoloop::controllers
