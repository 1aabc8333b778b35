#pragma once
// Dead reckoning of a differential-drive base from its wheels, as
// ros_controllers' diff_drive_controller computes it: each update takes the
// wheels' rotation since the last one (mean of each side's wheels, times its
// radius), turns it into a forward distance and a heading change, and
// integrates the pose exactly along the arc (second-order Runge-Kutta when the
// heading change is below 1e-6 rad). The velocities are the rolling mean of
// the last `window` per-update estimates. Real-time safe after resize().
#include <cstddef>
#include <vector>

namespace servoloop::controllers::diff_drive_controller {

class Odometry {
 public:
  // Non-real-time: the rolling-mean window (updates).
  void resize(std::size_t window);
  // Real-time.
  void setWheelParams(double separation, double left_radius, double right_radius) noexcept {
    separation_ = separation;
    left_radius_ = left_radius;
    right_radius_ = right_radius;
  }
  // Real-time: starts over at the origin from the wheels' current angles (rad).
  void reset(double left_angle, double right_angle, double time) noexcept;
  // Real-time: the wheels' angles now (rad, mean per side) at control time.
  void update(double left_angle, double right_angle, double time) noexcept;
  // Real-time: open loop, from the commanded velocities instead of the wheels.
  void updateOpenLoop(double linear, double angular, double time) noexcept;

  double x() const noexcept { return x_; }
  double y() const noexcept { return y_; }
  double heading() const noexcept { return heading_; }
  double linear() const noexcept { return linear_; }    // m/s, along the base's x
  double angular() const noexcept { return angular_; }  // rad/s

 private:
  void integrate(double distance, double turn) noexcept;
  double rollingMean(std::vector<double>& samples, double sample) noexcept;

  double separation_ = 1.0, left_radius_ = 1.0, right_radius_ = 1.0;
  double left_old_ = 0.0, right_old_ = 0.0;  // m travelled by each side
  double x_ = 0.0, y_ = 0.0, heading_ = 0.0;
  double linear_ = 0.0, angular_ = 0.0;
  double time_ = 0.0;
  std::vector<double> linear_samples_, angular_samples_;
  std::size_t next_ = 0, count_ = 0;
};

}  // namespace servoloop::controllers::diff_drive_controller
