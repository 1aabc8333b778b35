#pragma once
// One joint's motion between two points of a trajectory, interpolated the way
// ros_controllers' joint_trajectory_controller does it: by the polynomial of
// lowest degree that meets what the two points give.
//   - positions only: linear (constant velocity, no acceleration);
//   - positions and velocities: cubic (position and velocity at both ends);
//   - positions, velocities and accelerations: quintic (all three at both ends).
// Before its start a segment holds its start position, after its end its end
// position, both with zero velocity and acceleration; a segment of zero
// duration is its end point. Real-time safe: no allocation, no exception.
#include <array>

namespace servoloop::controllers {

// Position, velocity and acceleration of one joint at one time.
struct JointSample {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

enum class SplineKind { linear, cubic, quintic };

class SplineSegment {
 public:
  SplineSegment() = default;
  // start and end use only what `kind` needs (linear: positions; cubic: also
  // velocities; quintic: also accelerations). end_time < start_time is taken
  // as a segment of zero duration.
  SplineSegment(double start_time, const JointSample& start, double end_time, const JointSample& end,
                SplineKind kind) noexcept;

  JointSample sample(double time) const noexcept;
  // Whether its coefficients, and its state half way and at the end, are
  // finite: false when the points' values are so large (1e308) that
  // interpolating them overflows.
  bool finite() const noexcept;

  double startTime() const noexcept { return start_time_; }
  double endTime() const noexcept { return start_time_ + duration_; }
  SplineKind kind() const noexcept { return kind_; }

 private:
  // Position, velocity and acceleration of the polynomial at t from the start.
  JointSample evaluate(double t) const noexcept;

  std::array<double, 6> coefficients_{};  // position = sum c[i] * t^i, t from the start
  double start_time_ = 0.0;
  double duration_ = 0.0;
  SplineKind kind_ = SplineKind::linear;
};

}  // namespace servoloop::controllers
