#include "servoloop/controllers/joint_state_controller/joint_state_controller.hpp"

#include <algorithm>
#include <string>

#include "servoloop/plugin/plugin_register.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/controllers/common/controller_params.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::controllers {

namespace cm = controller_manager;

bool JointStateController::init(hardware_interface::JointStateInterface* hw,
                                const cm::ControllerContext& context) {
  // ros_controllers loads a rate of 0 and never publishes (kept, with a
  // warning below: a ROS YAML may say so on purpose); a negative rate is no
  // rate at all and is refused.
  const double rate = requirePublishRate(context);
  gate_.setRate(rate);

  std::vector<std::string> names = hw->getNames();
  std::sort(names.begin(), names.end());
  joints_.clear();
  prototype_ = servoloop::sensor_msgs::JointState{};
  for (const auto& name : names) {
    joints_.push_back(hw->getHandle(name));
    prototype_.name.push_back(name);
  }
  prototype_.position.assign(joints_.size(), 0.0);
  prototype_.velocity.assign(joints_.size(), 0.0);
  prototype_.effort.assign(joints_.size(), 0.0);
  readExtraJoints(context);

  if (context.topics != nullptr) {
    publisher_ = context.topics->advertise<servoloop::sensor_msgs::JointState>(
        namespaceTopic(context, "joint_states"), prototype_);
    // The staging message starts as the prototype: names and the extra
    // joints' constants are in place, update() only writes the measured values.
    publisher_.msg() = prototype_;
  }
  if (rate == 0.0) {
    logger().warn("controller '{}': publish_rate 0, so joint states are never published (as in ros_controllers); "
                  "give a rate in Hz, e.g. publish_rate: 50",
                  context.name);
  }
  return true;
}

void JointStateController::readExtraJoints(const cm::ControllerContext& context) {
  const params::Parameters extra = context.params.child("extra_joints");
  if (extra.empty()) return;
  const std::string path = parameterPath(context, "extra_joints");
  if (!extra.isList()) {
    throw ConfigError("controller '" + context.name + "': parameter '" + path +
                      "' must be a list of {name: ..., position: ..., velocity: ..., effort: ...}");
  }
  for (std::size_t i = 0; i < extra.size(); ++i) {
    const params::Parameters entry = extra.item(i);
    const std::string where = path + "[" + std::to_string(i) + "]";
    const params::Parameters name_node = entry.child("name");
    if (!name_node.isScalar()) {
      throw ConfigError("controller '" + context.name + "': '" + where +
                        "' needs a name, e.g. {name: gripper_finger, position: 0.0}");
    }
    const std::string name = name_node.as<std::string>();
    if (std::find(prototype_.name.begin(), prototype_.name.end(), name) != prototype_.name.end()) {
      // ros_control skips such an entry with an error; do the same so its YAML keeps loading.
      logger().error("controller '{}': extra joint '{}' ({}) is already published; skipping it",
                     context.name, name, where);
      continue;
    }
    double position = 0.0;
    double velocity = 0.0;
    double effort = 0.0;
    try {
      position = numberAt(entry.child("position"), where + "/position", 0.0);
      velocity = numberAt(entry.child("velocity"), where + "/velocity", 0.0);
      effort = numberAt(entry.child("effort"), where + "/effort", 0.0);
    } catch (const ConfigError& e) {
      throw ConfigError("controller '" + context.name + "': " + e.what());
    }
    prototype_.name.push_back(name);
    prototype_.position.push_back(position);
    prototype_.velocity.push_back(velocity);
    prototype_.effort.push_back(effort);
  }
}

void JointStateController::starting(const Time& /*time*/) { gate_.reset(); }

ReturnType JointStateController::update(const Time& time, const Duration& period) {
  if (!gate_.due(time, period) || !publisher_.valid()) return ReturnType::ok;
  // A busy staging message (another thread inspecting it) only skips this
  // publication, as realtime_tools does.
  if (!publisher_.trylock()) return ReturnType::ok;
  servoloop::sensor_msgs::JointState& msg = publisher_.msg();
  msg.stamp = time.seconds;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    msg.position[i] = joints_[i].getPosition();
    msg.velocity[i] = joints_[i].getVelocity();
    msg.effort[i] = joints_[i].getEffort();
  }
  publisher_.unlockAndPublish();
  return ReturnType::ok;
}

}  // namespace servoloop::controllers

SERVOLOOP_REGISTER_PLUGIN(servoloop::controllers::JointStateController,
                          servoloop::controller_manager::ControllerBase,
                          "joint_state_controller/JointStateController")
