// The real-time side of the controller manager allocates nothing: steady-state
// update() cycles with running controllers, carrying out a switch, and
// containing a fault (a NaN command) all run without touching the heap.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "alloc_counter.hpp"
#include "servoloop/controller_manager/controller.hpp"
#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/controller_manager/controller_manager.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"

namespace servoloop::controller_manager {
namespace {

namespace hi = servoloop::hardware_interface;

class TwoJointHW : public hi::RobotHW {
 public:
  TwoJointHW() {
    for (int i = 0; i < 2; ++i) {
      hi::JointStateHandle state("joint" + std::to_string(i + 1), &position[i], &velocity[i], &effort[i]);
      state_interface.registerHandle(state);
      effort_interface.registerHandle(hi::JointHandle(state, &command[i]));
    }
    registerInterface(&state_interface);
    registerInterface(&effort_interface);
  }
  void init(const hi::HardwareInfo&) override {}
  ReturnType read(Time, Duration) override { return ReturnType::ok; }
  ReturnType write(Time, Duration) override { return ReturnType::ok; }

  double position[2] = {0.1, 0.2};
  double velocity[2] = {0.0, 0.0};
  double effort[2] = {0.0, 0.0};
  double command[2] = {0.0, 0.0};
  hi::JointStateInterface state_interface;
  hi::EffortJointInterface effort_interface;
};

// A PD-like effort controller on one joint: effort = -gain * position - period.
// Writes NaN once `poison` is set.
class PdController : public Controller<hi::EffortJointInterface> {
 public:
  bool init(hi::EffortJointInterface* hw, const ControllerContext& context) override {
    joint_ = hw->getHandle(context.params["joint"].as<std::string>());
    gain_ = context.params["gain"].as<double>();
    return true;
  }
  void starting(const Time&) override { ++starts; }
  ReturnType update(const Time&, const Duration& period) override {
    ++updates;
    const double effort = poison ? std::numeric_limits<double>::quiet_NaN()
                                 : -gain_ * joint_.getPosition() - period.seconds;
    joint_.setCommand(effort);
    return ReturnType::ok;
  }
  void stopping(const Time&) override { ++stops; }

  bool poison = false;
  long starts = 0;
  long updates = 0;
  long stops = 0;

 private:
  hi::JointHandle joint_;
  double gain_ = 0.0;
};

class AllocationTest : public ::testing::Test {
 protected:
  AllocationTest() {
    auto factory = std::make_shared<InProcessControllerFactory>();
    factory->add<PdController>("test/PdController");
    params_ = YAML::Load(R"(
pd1: {type: test/PdController, joint: joint1, gain: 2.0}
pd2: {type: test/PdController, joint: joint2, gain: 3.0, update_rate: 100}
hold1: {type: test/PdController, joint: joint1, gain: 5.0}
guarded1: {type: test/PdController, joint: joint1, gain: 2.0, fallback_controllers: [hold1]}
)");
    manager_ = std::make_unique<ControllerManager>(&hw_, factory, ControllerManager::lookupIn(params_),
                                                   ControllerContext{}, 1000.0);
  }

  void cycle() {
    time_ += Duration(0.001);
    manager_->update(time_, Duration(0.001));
  }

  PdController* pd(const char* name) { return dynamic_cast<PdController*>(manager_->getController(name)); }

  TwoJointHW hw_;
  YAML::Node params_;
  std::unique_ptr<ControllerManager> manager_;
  Time time_;
};

// The counter must see an allocation when there is one, or the tests below
// could not fail.
TEST(AllocationCounter, SeesAnAllocationOnThisThread) {
  testing::AllocationCounter counter;
  auto* volatile probe = new double(1.0);
  delete probe;
  EXPECT_EQ(counter.allocations(), 1u);
}

TEST_F(AllocationTest, HundredThousandCyclesWithTwoRunningControllersAllocateNothing) {
  ASSERT_TRUE(manager_->loadController("pd1"));
  ASSERT_TRUE(manager_->loadController("pd2"));
  ASSERT_TRUE(manager_->requestSwitch(SwitchRequest{{"pd1", "pd2"}, {}, SwitchStrictness::STRICT, false, 0}));
  PdController* pd1 = pd("pd1");
  PdController* pd2 = pd("pd2");
  for (int i = 0; i < 10; ++i) cycle();  // start-up: the switch and the first updates

  std::size_t allocations = 0;
  {
    testing::AllocationCounter counter;  // counts this (the real-time) thread only
    for (int i = 0; i < 100000; ++i) cycle();
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(pd1->updates, 9 + 100000);
  EXPECT_EQ(pd2->updates, 10000);  // 100 Hz in a 1000 Hz manager: (9 + 100000) / 10 updates
  EXPECT_NEAR(hw_.command[0], -2.0 * 0.1 - 0.001, 1e-9);
  EXPECT_NEAR(hw_.command[1], -3.0 * 0.2 - 0.01, 1e-9);
}

TEST_F(AllocationTest, CarryingOutASwitchAndContainingAFaultAllocateNothing) {
  ASSERT_TRUE(manager_->loadController("pd1"));
  ASSERT_TRUE(manager_->loadController("pd2"));
  ASSERT_TRUE(manager_->requestSwitch(SwitchRequest{{"pd1", "pd2"}, {}, SwitchStrictness::STRICT, false, 0}));
  for (int i = 0; i < 20; ++i) cycle();
  // The request is validated off the real-time thread (that may allocate) ...
  ASSERT_TRUE(manager_->requestSwitch(SwitchRequest{{}, {"pd2"}, SwitchStrictness::STRICT, false, 0}));
  pd("pd1")->poison = true;

  std::size_t allocations = 0;
  {
    testing::AllocationCounter counter;
    // ... and carried out here: stopping pd2, then pd1's NaN is contained.
    for (int i = 0; i < 100; ++i) cycle();
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(pd("pd2")->stops, 1);
  EXPECT_EQ(pd("pd1")->state(), ControllerState::failed);
  EXPECT_DOUBLE_EQ(hw_.command[0], 0.0);
  EXPECT_EQ(manager_->processFaults().size(), 1u);
}

// A fault whose fallback controller is started in the same cycle, then a
// hundred cycles of the fallback running: nothing allocated.
TEST_F(AllocationTest, StartingAFallbackControllerAllocatesNothing) {
  ASSERT_TRUE(manager_->loadController("hold1"));
  ASSERT_TRUE(manager_->loadController("guarded1"));
  ASSERT_TRUE(manager_->requestSwitch(SwitchRequest{{"guarded1"}, {}, SwitchStrictness::STRICT, false, 0}));
  for (int i = 0; i < 20; ++i) cycle();
  pd("guarded1")->poison = true;

  std::size_t allocations = 0;
  {
    testing::AllocationCounter counter;
    for (int i = 0; i < 100; ++i) cycle();
    allocations = counter.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(pd("guarded1")->state(), ControllerState::failed);
  EXPECT_EQ(pd("hold1")->state(), ControllerState::running);
  EXPECT_EQ(pd("hold1")->starts, 1);
  EXPECT_EQ(pd("hold1")->updates, 99);  // every cycle after the one it started in
  EXPECT_DOUBLE_EQ(hw_.command[0], -5.0 * hw_.position[0] - 0.001);
  EXPECT_EQ(manager_->processFaults().size(), 1u);
}

}  // namespace
}  // namespace servoloop::controller_manager
