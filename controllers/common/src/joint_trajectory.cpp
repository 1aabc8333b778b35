#include "servoloop/controllers/common/joint_trajectory.hpp"

#include <cmath>

#include "servoloop/controllers/common/angles.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::controllers {
namespace {

void checkPoint(const TrajectoryPoint& point, std::size_t index, std::size_t joints, double previous_time) {
  const std::string where = "trajectory point " + std::to_string(index);
  const auto check = [&](const std::vector<double>& values, const char* field, bool may_be_empty) {
    if (values.empty() && may_be_empty) return;
    if (values.size() != joints) {
      throw Error(where + ": " + field + " has " + std::to_string(values.size()) + " values for " +
                  std::to_string(joints) + " joints; give one per joint" +
                  (may_be_empty ? " or none" : ""));
    }
    for (std::size_t j = 0; j < values.size(); ++j) {
      if (!std::isfinite(values[j])) {
        throw Error(where + ": " + field + "[" + std::to_string(j) + "] is not a finite number");
      }
    }
  };
  check(point.positions, "positions", false);
  check(point.velocities, "velocities", true);
  check(point.accelerations, "accelerations", true);
  if (!point.accelerations.empty() && point.velocities.empty()) {
    throw Error(where + ": accelerations without velocities; give velocities too (0 for none)");
  }
  if (!std::isfinite(point.time_from_start) || !(point.time_from_start > previous_time)) {
    throw Error(where + ": time_from_start " + std::to_string(point.time_from_start) +
                " must be finite and after the previous point's (" + std::to_string(previous_time) + " s)");
  }
}

SplineKind kindOf(const TrajectoryPoint& point) {
  if (!point.accelerations.empty()) return SplineKind::quintic;
  if (!point.velocities.empty()) return SplineKind::cubic;
  return SplineKind::linear;
}

}  // namespace

JointTrajectory JointTrajectory::fromPoints(double start_time, const std::vector<TrajectoryPoint>& points,
                                            std::size_t joint_count, const std::vector<bool>& continuous,
                                            const std::vector<bool>& held) {
  if ((!continuous.empty() && continuous.size() != joint_count) || (!held.empty() && held.size() != joint_count)) {
    throw Error("JointTrajectory: continuous or held flags do not match the " + std::to_string(joint_count) +
                " joints");
  }
  if (!std::isfinite(start_time)) throw Error("trajectory start time is not a finite number");
  double previous = -INFINITY;
  for (std::size_t i = 0; i < points.size(); ++i) {
    checkPoint(points[i], i, joint_count, previous);
    previous = points[i].time_from_start;
  }

  JointTrajectory trajectory;
  trajectory.start_time_ = start_time;
  trajectory.continuous_ = continuous.empty() ? std::vector<bool>(joint_count, false) : continuous;
  trajectory.held_ = held.empty() ? std::vector<bool>(joint_count, false) : held;
  trajectory.times_.reserve(points.size());
  for (const auto& point : points) trajectory.times_.push_back(point.time_from_start);
  trajectory.knots_.assign(joint_count, {});
  trajectory.segments_.assign(joint_count, {});
  trajectory.lead_.assign(joint_count, SplineSegment{});
  trajectory.offset_.assign(joint_count, 0.0);
  for (std::size_t j = 0; j < joint_count; ++j) {
    auto& knots = trajectory.knots_[j];
    auto& segments = trajectory.segments_[j];
    knots.reserve(points.size());
    segments.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const TrajectoryPoint& point = points[i];
      const JointSample state{point.positions[j], point.velocities.empty() ? 0.0 : point.velocities[j],
                              point.accelerations.empty() ? 0.0 : point.accelerations[j]};
      knots.push_back({state, kindOf(point)});
      if (i == 0) {
        segments.emplace_back();
      } else {
        segments.emplace_back(trajectory.times_[i - 1], knots[i - 1].state, trajectory.times_[i], state,
                              knots[i].kind);
      }
    }
  }
  return trajectory;
}

bool JointTrajectory::activate(double now, const std::vector<JointSample>& current) noexcept {
  const double start = start_time_ > 0.0 ? start_time_ : now;
  const double since_start = now - start;
  std::size_t first = 0;
  while (first < times_.size() && !(times_[first] > since_start)) ++first;
  if (first == times_.size() || current.size() < knots_.size()) return false;
  start_time_ = start;
  first_ = first;
  activation_time_ = now;
  for (std::size_t j = 0; j < knots_.size(); ++j) {
    const JointSample& from = current[j];
    if (held_[j]) {
      const JointSample rest{from.position, 0.0, 0.0};
      lead_[j] = SplineSegment(since_start, rest, since_start, rest, SplineKind::linear);
      continue;
    }
    const Knot& target = knots_[j][first];
    offset_[j] = 0.0;
    if (continuous_[j]) {
      // Whole turns that bring the first point the short way round.
      offset_[j] = from.position + shortestAngularDistance(from.position, target.state.position) -
                   target.state.position;
    }
    JointSample to = target.state;
    to.position += offset_[j];
    lead_[j] = SplineSegment(since_start, from, times_[first], to, target.kind);
  }
  return true;
}

void JointTrajectory::sample(double now, std::vector<JointSample>& out) const noexcept {
  const double time = now - start_time_;
  const std::size_t last = times_.empty() ? 0 : times_.size() - 1;
  for (std::size_t j = 0; j < knots_.size() && j < out.size(); ++j) {
    if (held_[j] || times_.empty() || time < times_[first_] || first_ == last) {
      out[j] = lead_[j].sample(time);
      continue;
    }
    // The segment that runs at `time`: the last one starting at or before it
    // (after the end, the last, which holds its end point).
    std::size_t lo = first_ + 1;
    std::size_t hi = times_.size();
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      if (segments_[j][mid].startTime() <= time) lo = mid;
      else hi = mid;
    }
    JointSample sample = segments_[j][lo].sample(time);
    sample.position += offset_[j];
    out[j] = sample;
  }
}

}  // namespace servoloop::controllers
