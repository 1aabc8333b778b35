#include "servoloop/controllers/diff_drive_controller/odometry.hpp"

#include <cmath>

namespace servoloop::controllers::diff_drive_controller {

void Odometry::resize(std::size_t window) {
  linear_samples_.assign(window == 0 ? 1 : window, 0.0);
  angular_samples_.assign(window == 0 ? 1 : window, 0.0);
  next_ = 0;
  count_ = 0;
}

void Odometry::reset(double left_angle, double right_angle, double time) noexcept {
  left_old_ = left_angle * left_radius_;
  right_old_ = right_angle * right_radius_;
  x_ = y_ = heading_ = 0.0;
  linear_ = angular_ = 0.0;
  time_ = time;
  next_ = 0;
  count_ = 0;
}

void Odometry::integrate(double distance, double turn) noexcept {
  if (std::abs(turn) < 1e-6) {
    const double direction = heading_ + 0.5 * turn;
    x_ += distance * std::cos(direction);
    y_ += distance * std::sin(direction);
    heading_ += turn;
    return;
  }
  const double heading_old = heading_;
  const double radius = distance / turn;
  heading_ += turn;
  x_ += radius * (std::sin(heading_) - std::sin(heading_old));
  y_ += -radius * (std::cos(heading_) - std::cos(heading_old));
}

double Odometry::rollingMean(std::vector<double>& samples, double sample) noexcept {
  samples[next_] = sample;
  double sum = 0.0;
  const std::size_t n = count_ < samples.size() ? count_ + 1 : samples.size();
  for (std::size_t i = 0; i < n; ++i) sum += samples[i];
  return sum / static_cast<double>(n);
}

void Odometry::update(double left_angle, double right_angle, double time) noexcept {
  const double left = left_angle * left_radius_;
  const double right = right_angle * right_radius_;
  const double left_step = left - left_old_;
  const double right_step = right - right_old_;
  left_old_ = left;
  right_old_ = right;
  const double distance = 0.5 * (right_step + left_step);
  const double turn = (right_step - left_step) / separation_;
  integrate(distance, turn);
  const double dt = time - time_;
  if (dt < 0.0001) return;  // too short an interval to estimate a speed from
  time_ = time;
  linear_ = rollingMean(linear_samples_, distance / dt);
  angular_ = rollingMean(angular_samples_, turn / dt);
  next_ = (next_ + 1) % linear_samples_.size();
  if (count_ < linear_samples_.size()) ++count_;
}

void Odometry::updateOpenLoop(double linear, double angular, double time) noexcept {
  const double dt = time - time_;
  time_ = time;
  linear_ = linear;
  angular_ = angular;
  integrate(linear * dt, angular * dt);
}

}  // namespace servoloop::controllers::diff_drive_controller
