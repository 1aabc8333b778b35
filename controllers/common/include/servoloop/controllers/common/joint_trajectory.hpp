#pragma once
// The trajectory a joint trajectory controller follows: for each of its
// joints, spline segments through the trajectory's points, led in from the
// state the controller commands when it takes the trajectory over, as
// ros_controllers' joint_trajectory_controller does.
//
// Two steps, so that the real-time thread never allocates:
//   - fromPoints() (non-real-time) checks the points and makes the segments
//     between them. The trajectory starts at its start time (0 or less: when
//     it is activated); each point is reached at start time + its
//     time_from_start.
//   - activate() (real-time) takes it over at `now` from the current desired
//     state: points not after now are dropped (they are history), and a
//     lead-in segment runs from the current state to the first point kept.
//     A continuous joint's points are shifted by whole turns so that the
//     first one is reached the short way round; the rest keep their
//     differences. Joints the trajectory does not name (a partial goal) hold
//     their current position.
// A segment is linear, cubic or quintic by what its end point gives
// (positions; also velocities; also accelerations). After the last point the
// trajectory holds the last point's position at rest.
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

  // Non-real-time. start_time: control time, s (<= 0: at activation). joint_count: the controller's joints (each point has a
  // value per joint); continuous: which joints wrap (empty: none); held:
  // joints the trajectory does not drive (empty: none; their values in the
  // points are not used). Throws servoloop::Error naming the point and field
  // when a point has the wrong number of values, a value is not finite,
  // accelerations come without velocities, or the times do not increase.
  static JointTrajectory fromPoints(double start_time, const std::vector<TrajectoryPoint>& points,
                                    std::size_t joint_count, const std::vector<bool>& continuous = {},
                                    const std::vector<bool>& held = {});

  // Real-time. Takes the trajectory over at now from current (one desired
  // state per joint). Returns false, and changes nothing, when no point is
  // after now.
  bool activate(double now, const std::vector<JointSample>& current) noexcept;

  // Real-time, after activate(). out must hold one sample per joint.
  void sample(double time, std::vector<JointSample>& out) const noexcept;

  std::size_t jointCount() const noexcept { return knots_.size(); }
  std::size_t pointCount() const noexcept { return times_.size(); }
  // When the trajectory starts (the reference of time_from_start) and when
  // its last point is reached.
  // (Before activation, a start time of 0 or less is still that.)
  double startTime() const noexcept { return start_time_; }
  double endTime() const noexcept { return start_time_ + (times_.empty() ? 0.0 : times_.back()); }
  // After activate(): points dropped because they were not after now, and
  // the time the lead-in segment starts.
  std::size_t droppedPoints() const noexcept { return first_; }
  double activationTime() const noexcept { return activation_time_; }

 private:
  struct Knot {
    JointSample state;
    SplineKind kind = SplineKind::linear;  // of the segment that ends here
  };

  // Times are from the start (time_from_start), segments too.
  std::vector<double> times_;                         // time_from_start of each point
  std::vector<std::vector<Knot>> knots_;              // [joint][point]
  std::vector<std::vector<SplineSegment>> segments_;  // [joint][point]: from the point before; [0] unused
  std::vector<SplineSegment> lead_;                   // [joint], made by activate()
  std::vector<double> offset_;                        // [joint] whole turns added to the points
  std::vector<bool> held_;
  std::vector<bool> continuous_;
  double start_time_ = 0.0;
  double activation_time_ = 0.0;
  std::size_t first_ = 0;  // first point kept
};

}  // namespace servoloop::controllers
