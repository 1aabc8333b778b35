#pragma once
// Test hardware and helpers for the controller tests: a RobotHW with plain
// joint storage that offers every joint interface, one with IMU and
// force-torque sensors, robot models built from inline URDF, and a
// ControllerContext maker.
#include <array>
#include <cstddef>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/controller_manager/controller_base.hpp"
#include "servoloop/controller_manager/controller_context.hpp"
#include "servoloop/realtime/topic_bus.hpp"
#include "servoloop/hardware_interface/force_torque_sensor_interface.hpp"
#include "servoloop/hardware_interface/imu_sensor_interface.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/params/parameters_yaml.hpp"

namespace servoloop::controllers::testing {

namespace hi = servoloop::hardware_interface;
namespace cm = servoloop::controller_manager;

// Joints with state storage (position, velocity, effort) and one command per
// interface, in joint space. Storage never moves after construction.
class TestJointsHW : public hi::RobotHW {
 public:
  explicit TestJointsHW(const std::vector<std::string>& joint_names)
      : names(joint_names),
        position(names.size(), 0.0),
        velocity(names.size(), 0.0),
        effort(names.size(), 0.0),
        effort_command(names.size(), 0.0),
        velocity_command(names.size(), 0.0),
        position_command(names.size(), 0.0) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      hi::JointStateHandle state(names[i], &position[i], &velocity[i], &effort[i]);
      state_interface.registerHandle(state);
      effort_interface.registerHandle(hi::JointHandle(state, &effort_command[i]));
      velocity_interface.registerHandle(hi::JointHandle(state, &velocity_command[i]));
      position_interface.registerHandle(hi::JointHandle(state, &position_command[i]));
    }
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
    registerInterface(&velocity_interface);
    registerInterface(&position_interface);
  }

  void init(const hi::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }

  std::size_t index(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return i;
    }
    ADD_FAILURE() << "no joint " << name;
    return 0;
  }

  std::vector<std::string> names;
  std::vector<double> position, velocity, effort;
  std::vector<double> effort_command, velocity_command, position_command;
  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;
  hi::VelocityJointInterface velocity_interface;
  hi::PositionJointInterface position_interface;
};

// IMUs and force-torque sensors whose readings the test writes into plain
// storage. Storage never moves after it is added.
class TestSensorsHW : public hi::RobotHW {
 public:
  struct ImuStorage {
    std::array<double, 4> orientation{0.0, 0.0, 0.0, 1.0};  // x, y, z, w
    std::array<double, 9> orientation_covariance{};
    std::array<double, 3> angular_velocity{};  // rad/s
    std::array<double, 9> angular_velocity_covariance{};
    std::array<double, 3> linear_acceleration{};  // m/s²
    std::array<double, 9> linear_acceleration_covariance{};
  };
  struct ForceTorqueStorage {
    std::array<double, 3> force{};   // N
    std::array<double, 3> torque{};  // N·m
  };

  TestSensorsHW() {
    registerInterface(&imu_interface);
    registerInterface(&force_torque_interface);
  }

  // An IMU that measures everything, covariances included.
  ImuStorage& addImu(const std::string& name, const std::string& frame_id) {
    ImuStorage& storage = imus.emplace_back();
    hi::ImuSensorHandle::Data data;
    data.name = name;
    data.frame_id = frame_id;
    data.orientation = storage.orientation.data();
    data.orientation_covariance = storage.orientation_covariance.data();
    data.angular_velocity = storage.angular_velocity.data();
    data.angular_velocity_covariance = storage.angular_velocity_covariance.data();
    data.linear_acceleration = storage.linear_acceleration.data();
    data.linear_acceleration_covariance = storage.linear_acceleration_covariance.data();
    imu_interface.registerHandle(hi::ImuSensorHandle(data));
    return storage;
  }
  // An IMU that gives only what `data` points to (e.g. a gyro: angular velocity only).
  void addImu(const hi::ImuSensorHandle::Data& data) { imu_interface.registerHandle(hi::ImuSensorHandle(data)); }

  ForceTorqueStorage& addForceTorque(const std::string& name, const std::string& frame_id) {
    ForceTorqueStorage& storage = force_torques.emplace_back();
    force_torque_interface.registerHandle(
        hi::ForceTorqueSensorHandle(name, frame_id, storage.force.data(), storage.torque.data()));
    return storage;
  }

  void init(const hi::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }

  std::deque<ImuStorage> imus;
  std::deque<ForceTorqueStorage> force_torques;
  hi::ImuSensorInterface imu_interface;
  hi::ForceTorqueSensorInterface force_torque_interface;
};

// A URDF with one joint of each kind the controllers handle:
//   rev      revolute,   limits [0, 2] rad (as the seed's joint1)
//   cont     continuous
//   slide    prismatic,  limits [-0.5, 0.5] m
//   wide     revolute,   limits [-4, 4] rad (more than a full turn)
inline std::shared_ptr<const urdf::ModelInterface> testRobotModel() {
  const char* link_body =
      R"(<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>)";
  std::string xml = R"(<?xml version="1.0"?><robot name="test_robot"><link name="base"/>)";
  const char* joints[][3] = {{"rev", "revolute", R"(<limit lower="0" upper="2" effort="10" velocity="1"/>)"},
                             {"cont", "continuous", ""},
                             {"slide", "prismatic", R"(<limit lower="-0.5" upper="0.5" effort="10" velocity="1"/>)"},
                             {"wide", "revolute", R"(<limit lower="-4" upper="4" effort="10" velocity="1"/>)"}};
  for (const auto& joint : joints) {
    const std::string name = joint[0];
    xml += "<link name=\"" + name + "_link\">" + link_body + "</link>";
    xml += "<joint name=\"" + name + "\" type=\"" + joint[1] + "\"><parent link=\"base\"/><child link=\"" +
           name + "_link\"/><axis xyz=\"0 0 1\"/>" + joint[2] + "</joint>";
  }
  xml += "</robot>";
  return servoloop::parseRobotModel(xml, "test_robot.urdf");
}

// The seed robot (revolute joint1, limits [0, 2]).
inline std::shared_ptr<const urdf::ModelInterface> seedRobotModel() {
  return servoloop::loadRobotModelFile(std::string(SERVOLOOP_SOURCE_DIR) +
                                       "/robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf");
}

// The seed's controller YAML, robot namespace node (one_DOF_robot).
inline YAML::Node seedControllerParams() {
  return YAML::LoadFile(std::string(SERVOLOOP_SOURCE_DIR) +
                        "/robots/one_dof/control_config/one_dof_ctl_params.yaml")["one_DOF_robot"];
}

inline cm::ControllerContext makeContext(const std::string& name, const std::string& params_yaml,
                                         servoloop::realtime::TopicBus* topics,
                                         std::shared_ptr<const urdf::ModelInterface> model = nullptr,
                                         const std::string& robot_namespace = "/robot") {
  cm::ControllerContext context;
  context.name = name;
  context.robot_namespace = robot_namespace;
  context.params = servoloop::params::parametersFromYaml(YAML::Load(params_yaml), robot_namespace + "/" + name);
  context.topics = topics;
  context.robot_model = std::move(model);
  return context;
}

// Runs the controller's initRequest on hw; fails the test when it returns false.
inline void initController(cm::ControllerBase& controller, hi::RobotHW& hw,
                           const cm::ControllerContext& context) {
  std::vector<hi::InterfaceResources> claimed;
  ASSERT_TRUE(controller.initRequest(&hw, context, claimed));
}

// Runs the controller's updates first..last at 1 kHz (control time k·1 ms),
// flushes `bus`, and returns the numbers of the updates that published
// (the controller's publishedCount() grew).
template <class Controller>
std::vector<int> updatesThatPublishAt1kHz(Controller& controller, servoloop::realtime::TopicBus& bus, int first,
                                          int last) {
  std::vector<int> published;
  for (int k = first; k <= last; ++k) {
    const auto before = controller.publishedCount();
    EXPECT_EQ(controller.update(Time(0.001 * k), Duration(0.001)), ReturnType::ok);
    if (controller.publishedCount() != before) published.push_back(k);
  }
  bus.flush();
  return published;
}

}  // namespace servoloop::controllers::testing
