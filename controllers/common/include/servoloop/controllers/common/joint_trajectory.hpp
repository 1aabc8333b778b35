#pragma once
// The trajectory a joint trajectory controller follows: for each of its
// joints, the spline segments from the state it commands when a trajectory
// arrives, through the trajectory's points, as ros_controllers'
// joint_trajectory_controller builds them.
//
//   - The trajectory starts at its start time (0 or less: now); each point is
//     reached at start time + its time_from_start.
//   - Points not after now are dropped (they are history); a trajectory with
//     no point after now is empty and changes nothing.
//   - The first segment runs from the current state at now to the first point
//     kept; then one segment per pair of points.
//   - A segment is linear, cubic or quintic by what its end point gives
//     (positions; also velocities; also accelerations).
//   - A continuous joint's points are shifted by whole turns so that the
//     first one is reached the short way round; the rest keep their
//     differences.
//   - Before now it holds the current position at rest; after the last point
//     it holds the last point's position at rest.
// Built outside the real-time thread (it allocates and throws); sampled on it.
#include <cstddef>
#include <string>
#include <vector>

#include "servoloop/controllers/common/spline_segment.hpp"

namespace servoloop::controllers {

struct TrajectoryPoint {
  std::vector<double> positions;      // one per joint
  std::vector<double> velocities;     // empty, or one per joint
  std::vector<double> accelerations;  // empty, or one per joint (then velocities too)
  double time_from_start = 0.0;       // s
};

class JointTrajectory {
 public:
  JointTrajectory() = default;

  // Non-real-time. current: the state commanded now, one per joint;
  // continuous: which joints wrap (empty: none). Throws servoloop::Error
  // naming the point and field when a point has the wrong number of values,
  // a value is not finite, accelerations come without velocities, or the
  // times do not increase.
  static JointTrajectory build(double now, double start_time, const std::vector<JointSample>& current,
                               const std::vector<TrajectoryPoint>& points, const std::vector<bool>& continuous = {});

  // Real-time. out must hold one sample per joint.
  void sample(double time, std::vector<JointSample>& out) const noexcept;

  bool empty() const noexcept { return segments_.empty() || segments_.front().empty(); }
  std::size_t jointCount() const noexcept { return segments_.size(); }
  std::size_t segmentCount() const noexcept { return empty() ? 0 : segments_.front().size(); }
  // The time of the last point (the trajectory's end); now when empty.
  double endTime() const noexcept { return end_time_; }
  // Points dropped because they were not after now.
  std::size_t droppedPoints() const noexcept { return dropped_points_; }

 private:
  std::vector<std::vector<SplineSegment>> segments_;  // [joint][segment], in time order
  double end_time_ = 0.0;
  std::size_t dropped_points_ = 0;
};

}  // namespace servoloop::controllers
