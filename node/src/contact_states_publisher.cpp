#include "servoloop/node/contact_states_publisher.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "servoloop/params/parameter_store.hpp"

namespace servoloop::node {
namespace {
geometry_msgs::Vector3 vector3(const double* v) { return {v[0], v[1], v[2]}; }
}  // namespace

ContactStatesPublisher::ContactStatesPublisher(hardware_interface::ContactSensorInterface& sensors,
                                               realtime::TopicBus& bus, const std::string& robot_namespace,
                                               double time_step_s, std::uint64_t steps_per_cycle)
    : bus_(bus), time_step_s_(time_step_s) {
  for (const std::string& name : sensors.getNames()) {
    Sensor sensor{sensors.getHandle(name), "", std::max<std::uint64_t>(1, steps_per_cycle), 0};
    sensor.topic = params::resolveName(robot_namespace, sensor.handle.getTopic());
    const double rate = sensor.handle.getUpdateRate();
    if (rate > 0.0) {
      sensor.steps_per_message = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(1.0 / (rate * time_step_s))));
    }
    sensors_.push_back(std::move(sensor));
  }
}

gazebo_msgs::ContactsState ContactStatesPublisher::message(const hardware_interface::ContactSensorHandle& sensor,
                                                          double stamp_s) {
  const hardware_interface::ContactSensorReading& reading = sensor.getReading();
  gazebo_msgs::ContactsState msg;
  msg.stamp = stamp_s;
  msg.frame_id = sensor.getFrameId();
  for (std::size_t k = 0; k < reading.count; ++k) {
    const hardware_interface::ContactPoint& point = reading.points[k];
    const std::string_view other(point.other_collision.data());
    auto state = std::find_if(msg.states.begin(), msg.states.end(),
                              [&](const gazebo_msgs::ContactState& s) { return s.collision2_name == other; });
    if (state == msg.states.end()) {
      gazebo_msgs::ContactState added;
      added.collision1_name = sensor.getCollision();
      added.collision2_name = std::string(other);
      added.info = "contacts of " + added.collision1_name + " with " + added.collision2_name;
      msg.states.push_back(std::move(added));
      state = std::prev(msg.states.end());
    }
    geometry_msgs::Wrench wrench;
    wrench.force = vector3(point.force);
    // The torque about the sensor link's origin: (p - o) × f.
    const double r[3] = {point.position[0] - reading.link_position[0], point.position[1] - reading.link_position[1],
                         point.position[2] - reading.link_position[2]};
    wrench.torque = {r[1] * point.force[2] - r[2] * point.force[1], r[2] * point.force[0] - r[0] * point.force[2],
                     r[0] * point.force[1] - r[1] * point.force[0]};
    state->wrenches.push_back(wrench);
    state->contact_positions.push_back(vector3(point.position));
    state->contact_normals.push_back(vector3(point.normal));
    state->depths.push_back(point.depth);
    geometry_msgs::Wrench& total = state->total_wrench;
    total.force = {total.force.x + wrench.force.x, total.force.y + wrench.force.y, total.force.z + wrench.force.z};
    total.torque = {total.torque.x + wrench.torque.x, total.torque.y + wrench.torque.y,
                    total.torque.z + wrench.torque.z};
  }
  return msg;
}

std::uint64_t ContactStatesPublisher::publishDue(std::uint64_t steps_taken) {
  if (steps_taken < last_steps_) restart();  // the world went back (a reset)
  last_steps_ = steps_taken;
  std::uint64_t until_next = UINT64_MAX;
  for (Sensor& sensor : sensors_) {
    if (steps_taken >= sensor.next_step) {
      bus_.publish(sensor.topic, message(sensor.handle, static_cast<double>(steps_taken) * time_step_s_));
      sensor.next_step = (steps_taken / sensor.steps_per_message + 1) * sensor.steps_per_message;
    }
    until_next = std::min(until_next, sensor.next_step - steps_taken);
  }
  return std::max<std::uint64_t>(1, until_next);
}

void ContactStatesPublisher::restart() noexcept {
  for (Sensor& sensor : sensors_) sensor.next_step = 0;
}

std::vector<std::string> ContactStatesPublisher::topics() const {
  std::vector<std::string> out;
  for (const Sensor& sensor : sensors_) out.push_back(sensor.topic);
  return out;
}

}  // namespace servoloop::node
