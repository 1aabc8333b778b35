#include "compare_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Largest |difference| with where it occurs, and the running sum of squares.
// A non-finite difference (a run that diverged) counts as infinitely large
// from its first occurrence on.
struct DifferenceStatistic {
  double max_abs = 0.0;
  double max_signed = 0.0;
  double max_time_s = 0.0;
  double sum_squares = 0.0;
  std::size_t count = 0;

  void add(double difference, double time_s) {
    ++count;
    if (!std::isfinite(difference)) {
      if (std::isfinite(max_abs)) {
        max_abs = std::numeric_limits<double>::infinity();
        max_signed = difference;
        max_time_s = time_s;
      }
      sum_squares = std::numeric_limits<double>::infinity();
      return;
    }
    sum_squares += difference * difference;
    if (std::abs(difference) > max_abs) {
      max_abs = std::abs(difference);
      max_signed = difference;
      max_time_s = time_s;
    }
  }
  double rms() const { return count == 0 ? 0.0 : std::sqrt(sum_squares / static_cast<double>(count)); }
};

// Where a stamp falls among B's samples: between sample `index` and the next,
// `fraction` of the way; `offset_s` is the distance to the nearer sample.
struct Alignment {
  std::size_t index = 0;
  double fraction = 0.0;
  double offset_s = 0.0;

  double valueOf(const std::vector<double>& series) const {
    if (fraction == 0.0) return series[index];
    return series[index] + fraction * (series[index + 1] - series[index]);
  }
};

// `t` must lie within the span of `stamps`; the search starts at `from`
// (stamps are increasing, so walking A's stamps in order is linear overall).
Alignment align(const std::vector<double>& stamps, double t, std::size_t from, double epsilon_s) {
  Alignment at;
  at.index = from;
  while (at.index + 1 < stamps.size() && stamps[at.index + 1] <= t + epsilon_s) ++at.index;
  const double before = t - stamps[at.index];
  if (before > epsilon_s && at.index + 1 < stamps.size()) {
    const double span = stamps[at.index + 1] - stamps[at.index];
    at.fraction = before / span;
    at.offset_s = std::min(before, span - before);
  }
  return at;
}

}  // namespace

std::size_t JointTrajectory::jointIndex(const std::string& joint) const {
  return static_cast<std::size_t>(std::find(joints.begin(), joints.end(), joint) - joints.begin());
}

void JointTrajectory::append(double stamp_s, const std::vector<std::string>& names,
                             const std::vector<double>& positions, const std::vector<double>& velocities) {
  if (joints.empty()) {
    joints = names;
    units.resize(joints.size(), "rad");
    position.resize(joints.size());
    velocity.resize(joints.size());
  }
  time_s.push_back(stamp_s);
  for (auto& column : position) column.push_back(kNaN);
  for (auto& column : velocity) column.push_back(kNaN);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::size_t j = jointIndex(names[k]);
    if (j == joints.size()) continue;
    if (k < positions.size()) position[j].back() = positions[k];
    if (k < velocities.size()) velocity[j].back() = velocities[k];
  }
}

void JointTrajectory::sortByStamp() {
  std::vector<std::size_t> order(time_s.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return time_s[x] < time_s[y]; });
  std::vector<std::size_t> kept;
  for (std::size_t i : order) {
    if (kept.empty() || time_s[i] != time_s[kept.back()]) kept.push_back(i);
  }
  const auto pick = [&](const std::vector<double>& column) {
    std::vector<double> out;
    out.reserve(kept.size());
    for (std::size_t i : kept) out.push_back(column[i]);
    return out;
  };
  time_s = pick(time_s);
  for (auto& column : position) column = pick(column);
  for (auto& column : velocity) column = pick(column);
}

TopicComparison compareTrajectories(const JointTrajectory& a, const JointTrajectory& b) {
  TopicComparison out;
  out.topic = a.topic;
  if (a.samples() == 0 || b.samples() == 0) {
    throw Error("topic '" + a.topic + "': " + (a.samples() == 0 ? "the first" : "the second") +
                " run recorded no message, so there is nothing to compare");
  }

  // Joints both runs have, in A's order, with their column in B.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t ja = 0; ja < a.joints.size(); ++ja) {
    const std::size_t jb = b.jointIndex(a.joints[ja]);
    if (jb < b.joints.size()) pairs.emplace_back(ja, jb);
  }
  if (pairs.empty()) throw Error("topic '" + a.topic + "': the two runs share no joint name");

  const double b_first = b.time_s.front();
  const double b_last = b.time_s.back();
  // Stamps closer than this count as equal (they are sums of the same steps).
  const double stamp_epsilon = 1e-9 * std::max(1.0, std::abs(b_last));
  std::vector<DifferenceStatistic> position_stats(pairs.size()), velocity_stats(pairs.size());
  out.position_difference.resize(pairs.size());
  Alignment at;
  Alignment last;
  std::size_t last_compared = 0;
  for (std::size_t i = 0; i < a.samples(); ++i) {
    const double t = a.time_s[i];
    if (t < b_first - stamp_epsilon || t > b_last + stamp_epsilon) continue;
    at = align(b.time_s, t, at.index, stamp_epsilon);
    out.max_stamp_offset_s = std::max(out.max_stamp_offset_s, at.offset_s);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const auto [ja, jb] = pairs[p];
      const double position_difference = at.valueOf(b.position[jb]) - a.position[ja][i];
      position_stats[p].add(position_difference, t);
      out.position_difference[p].push_back(position_difference);
      velocity_stats[p].add(at.valueOf(b.velocity[jb]) - a.velocity[ja][i], t);
    }
    out.time_s.push_back(t);
    if (out.samples == 0) out.start_time_s = t;
    out.end_time_s = t;
    last = at;
    last_compared = i;
    ++out.samples;
  }
  if (out.samples == 0) {
    throw Error("topic '" + a.topic + "': the runs do not overlap in time (first run " +
                std::to_string(a.time_s.front()) + " to " + std::to_string(a.time_s.back()) + " s, second " +
                std::to_string(b_first) + " to " + std::to_string(b_last) + " s)");
  }

  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [ja, jb] = pairs[p];
    JointDifference d;
    d.joint = a.joints[ja];
    d.unit = ja < a.units.size() ? a.units[ja] : "rad";
    d.max_position_difference = position_stats[p].max_abs;
    d.max_position_signed = position_stats[p].max_signed;
    d.max_position_time_s = position_stats[p].max_time_s;
    d.rms_position_difference = position_stats[p].rms();
    d.max_velocity_difference = velocity_stats[p].max_abs;
    d.max_velocity_time_s = velocity_stats[p].max_time_s;
    d.rms_velocity_difference = velocity_stats[p].rms();
    d.final_position_a = a.position[ja][last_compared];
    d.final_position_b = last.valueOf(b.position[jb]);
    out.joints.push_back(d);
  }
  return out;
}

}  // namespace servoloop::cli
