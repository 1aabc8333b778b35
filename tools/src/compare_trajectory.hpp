#pragma once
// Joint-state trajectories of one run and how two of them differ, for
// `servoloop compare`: samples aligned by stamp, per joint the largest
// |Δposition| and |Δvelocity| with the time they occur, and their RMS.
// Non-real-time; plain data, no simulation.
#include <cstddef>
#include <string>
#include <vector>

namespace servoloop::cli {

// The sensor_msgs/JointState messages of one topic over one run.
struct JointTrajectory {
  std::string topic;                        // e.g. /one_DOF_robot/joint_states
  std::vector<std::string> joints;          // joint names, in message order
  std::vector<std::string> units;           // per joint: "rad" or "m" (position; velocity adds "/s")
  std::vector<double> time_s;               // message stamps, simulated s, increasing
  std::vector<std::vector<double>> position;  // [joint][sample], rad or m
  std::vector<std::vector<double>> velocity;  // [joint][sample], rad/s or m/s

  std::size_t samples() const { return time_s.size(); }
  // Index of `joint` in joints, or joints.size() when absent.
  std::size_t jointIndex(const std::string& joint) const;
  // Appends one message's values, given in `names` order (joints unknown so
  // far are ignored, missing ones get NaN). The first call fixes the joints
  // when none are set.
  void append(double stamp_s, const std::vector<std::string>& names, const std::vector<double>& positions,
              const std::vector<double>& velocities);
  // Orders the samples by stamp and keeps the first of each stamp. A topic
  // with two publishers arrives interleaved, with repeated stamps (the seed's
  // raw PD publishes <ns>/joint_states next to the joint_state_controller).
  void sortByStamp();
};

// How one joint differs between run A and run B (differences are B − A).
struct JointDifference {
  std::string joint;
  std::string unit;                        // position unit: rad or m
  double max_position_difference = 0.0;    // max |qB − qA|
  double max_position_time_s = 0.0;        // where it occurs
  double max_position_signed = 0.0;        // qB − qA there
  double rms_position_difference = 0.0;
  double max_velocity_difference = 0.0;    // max |vB − vA|
  double max_velocity_time_s = 0.0;
  double rms_velocity_difference = 0.0;
  double final_position_a = 0.0;           // at the last compared sample
  double final_position_b = 0.0;
};

struct TopicComparison {
  std::string topic;
  std::size_t samples = 0;       // samples of A compared (those inside B's time span)
  double start_time_s = 0.0;     // first and last compared stamp
  double end_time_s = 0.0;
  double max_stamp_offset_s = 0.0;  // largest distance from an A stamp to the nearest B stamp
  std::vector<JointDifference> joints;  // A's joint order, joints both runs have
  // The aligned differences themselves, for plotting: the compared stamps and
  // per joint (in `joints` order) qB − qA at each.
  std::vector<double> time_s;
  std::vector<std::vector<double>> position_difference;  // [joint][sample]
};

// Aligns B onto A's stamps: every A sample inside B's time span is compared
// with B linearly interpolated at that stamp (exact when the stamps coincide,
// as they do for two runs of one launch file: the joint state controller
// publishes on the same control cycles on every backend). Joints are matched
// by name. Throws servoloop::Error naming the topic when either run has no
// sample, the runs share no joint, or their time spans do not overlap.
TopicComparison compareTrajectories(const JointTrajectory& a, const JointTrajectory& b);

}  // namespace servoloop::cli
