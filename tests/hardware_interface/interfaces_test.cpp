#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/actuator_interfaces.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"

namespace hi = servoloop::hardware_interface;

namespace {
struct TwoJointStorage {
  double pos[2] = {0.5, -1.0};
  double vel[2] = {0.1, 0.2};
  double eff[2] = {2.0, 3.0};
  double cmd[2] = {0.0, 0.0};
};

class TwoJointHW : public hi::RobotHW {
 public:
  void init(const hi::HardwareInfo&) override {
    for (int i = 0; i < 2; ++i) {
      const std::string name = "joint" + std::to_string(i + 1);
      hi::JointStateHandle state(name, &s.pos[i], &s.vel[i], &s.eff[i]);
      state_interface.registerHandle(state);
      effort_interface.registerHandle(hi::JointHandle(state, &s.cmd[i]));
    }
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
  }
  servoloop::ReturnType read(servoloop::Time, servoloop::Duration) override {
    return servoloop::ReturnType::ok;
  }
  servoloop::ReturnType write(servoloop::Time, servoloop::Duration) override {
    return servoloop::ReturnType::ok;
  }
  TwoJointStorage s;
  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;
};
}  // namespace

TEST(JointHandles, ReadAndCommandThroughStorage) {
  TwoJointHW hw;
  hw.init({});
  auto handle = hw.get<hi::EffortJointInterface>()->getHandle("joint2");
  EXPECT_EQ(handle.getName(), "joint2");
  EXPECT_DOUBLE_EQ(handle.getPosition(), -1.0);
  EXPECT_DOUBLE_EQ(handle.getVelocity(), 0.2);
  EXPECT_DOUBLE_EQ(handle.getEffort(), 3.0);
  handle.setCommand(4.5);
  EXPECT_DOUBLE_EQ(hw.s.cmd[1], 4.5);
  hw.s.pos[1] = 7.0;
  EXPECT_DOUBLE_EQ(handle.getPosition(), 7.0);
}

TEST(JointHandles, NullDataIsRejectedWithTheHandleName) {
  double x = 0;
  try {
    hi::JointStateHandle h("elbow", &x, nullptr, &x);
    FAIL() << "expected an error";
  } catch (const servoloop::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'elbow'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("velocity"), std::string::npos) << e.what();
  }
  hi::JointStateHandle ok("elbow", &x, &x, &x);
  EXPECT_THROW(hi::JointHandle(ok, nullptr), servoloop::Error);
}

TEST(Interfaces, UnknownHandleNamesHandleAndInterface) {
  TwoJointHW hw;
  hw.init({});
  try {
    hw.get<hi::EffortJointInterface>()->getHandle("joint9");
    FAIL() << "expected UnknownHandleError";
  } catch (const servoloop::UnknownHandleError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("EffortJointInterface"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'joint9'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("joint1, joint2"), std::string::npos) << msg;
  }
}

TEST(Interfaces, CommandInterfacesClaimStateInterfaceDoesNot) {
  TwoJointHW hw;
  hw.init({});
  hw.get<hi::JointStateInterface>()->getHandle("joint1");
  EXPECT_TRUE(hw.state_interface.getClaims().empty());
  hw.get<hi::EffortJointInterface>()->getHandle("joint1");
  EXPECT_EQ(hw.effort_interface.getClaims(), std::set<std::string>{"joint1"});
  hw.effort_interface.clearClaims();
  EXPECT_TRUE(hw.effort_interface.getClaims().empty());
}

TEST(Interfaces, LookupByTypeAndName) {
  TwoJointHW hw;
  hw.init({});
  EXPECT_EQ(hw.get<hi::VelocityJointInterface>(), nullptr);
  EXPECT_EQ(hw.getByName("EffortJointInterface"), &hw.effort_interface);
  EXPECT_EQ(hw.getNames(), (std::vector<std::string>{"EffortJointInterface", "JointStateInterface"}));
  EXPECT_EQ(hw.effort_interface.getNames(), (std::vector<std::string>{"joint1", "joint2"}));
}

TEST(RobotHW, ConflictIsAResourceClaimedByTwoControllers) {
  TwoJointHW hw;
  using CI = hi::ControllerInfo;
  const CI a{"a", "t", {{"EffortJointInterface", {"joint1"}}}};
  const CI b{"b", "t", {{"EffortJointInterface", {"joint2"}}}};
  const CI c{"c", "t", {{"VelocityJointInterface", {"joint1"}}}};
  // A controller claiming the same joint through two interfaces is not a conflict.
  const CI d{"d", "t", {{"EffortJointInterface", {"joint2"}}, {"PositionJointInterface", {"joint2"}}}};
  // A state-only controller claims nothing.
  const CI js{"js", "t", {}};
  EXPECT_FALSE(hw.checkForConflict({a, b, js}));
  EXPECT_TRUE(hw.checkForConflict({a, c}));
  EXPECT_FALSE(hw.checkForConflict({a, d}));
  EXPECT_TRUE(hw.checkForConflict({b, d}));
}

TEST(ActuatorInterfaces, ClaimAndLookup) {
  double p = 1, v = 2, e = 3, cmd = 0;
  hi::ActuatorStateHandle state("motor1", &p, &v, &e);
  hi::EffortActuatorInterface effort;
  effort.registerHandle(hi::ActuatorHandle(state, &cmd));
  auto h = effort.getHandle("motor1");
  h.setCommand(-2.5);
  EXPECT_DOUBLE_EQ(cmd, -2.5);
  EXPECT_EQ(effort.getClaims(), std::set<std::string>{"motor1"});
  EXPECT_THROW(effort.getHandle("motor2"), servoloop::UnknownHandleError);
}
