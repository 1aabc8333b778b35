// The three transmissions against hand-computed cases of ros_control's
// transmission_interface formulas, plus inverse
// round trips and rejection of zero reductions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>

#include "servoloop/core/errors.hpp"
#include "servoloop/transmissions/differential_transmission.hpp"
#include "servoloop/transmissions/four_bar_linkage_transmission.hpp"
#include "servoloop/transmissions/simple_transmission.hpp"

namespace st = servoloop::transmissions;

namespace {

// Value storage for one transmission with up to two actuators and two joints.
struct Values {
  std::array<double, 2> actuator_position{};
  std::array<double, 2> actuator_velocity{};
  std::array<double, 2> actuator_effort{};
  std::array<double, 2> joint_position{};
  std::array<double, 2> joint_velocity{};
  std::array<double, 2> joint_effort{};
  st::ActuatorData actuator;
  st::JointData joint;

  explicit Values(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      actuator.position.push_back(&actuator_position[i]);
      actuator.velocity.push_back(&actuator_velocity[i]);
      actuator.effort.push_back(&actuator_effort[i]);
      joint.position.push_back(&joint_position[i]);
      joint.velocity.push_back(&joint_velocity[i]);
      joint.effort.push_back(&joint_effort[i]);
    }
  }
  void setActuators(double a1, double a2) {
    actuator_position = actuator_velocity = actuator_effort = {a1, a2};
  }
  void setJoints(double j1, double j2) {
    joint_position = joint_velocity = joint_effort = {j1, j2};
  }
};

void actuatorToJoint(const st::Transmission& t, Values& v) {
  t.actuatorToJointEffort(v.actuator, v.joint);
  t.actuatorToJointVelocity(v.actuator, v.joint);
  t.actuatorToJointPosition(v.actuator, v.joint);
}

void jointToActuator(const st::Transmission& t, Values& v) {
  t.jointToActuatorEffort(v.joint, v.actuator);
  t.jointToActuatorVelocity(v.joint, v.actuator);
  t.jointToActuatorPosition(v.joint, v.actuator);
}

constexpr double kTol = 1e-12;

}  // namespace

// --- Simple: n = 10, o = 1, actuator 1 → effort 10, velocity 0.1, position 1.1.

TEST(SimpleTransmission, ReferenceCaseActuatorToJoint) {
  const st::SimpleTransmission t(10.0, 1.0);
  EXPECT_EQ(t.numActuators(), 1u);
  EXPECT_EQ(t.numJoints(), 1u);
  Values v(1);
  v.setActuators(1.0, 0.0);
  actuatorToJoint(t, v);
  EXPECT_NEAR(v.joint_effort[0], 10.0, kTol);
  EXPECT_NEAR(v.joint_velocity[0], 0.1, kTol);
  EXPECT_NEAR(v.joint_position[0], 1.1, kTol);
}

TEST(SimpleTransmission, ReferenceCaseJointToActuator) {
  const st::SimpleTransmission t(10.0, 1.0);
  Values v(1);
  v.joint_effort[0] = 10.0;
  v.joint_velocity[0] = 0.1;
  v.joint_position[0] = 1.1;
  jointToActuator(t, v);
  EXPECT_NEAR(v.actuator_effort[0], 1.0, kTol);
  EXPECT_NEAR(v.actuator_velocity[0], 1.0, kTol);
  EXPECT_NEAR(v.actuator_position[0], 1.0, kTol);
}

TEST(SimpleTransmission, FiftyToOneScalesEffortUpAndMotionDown) {
  const st::SimpleTransmission t(50.0);
  Values v(1);
  v.actuator_effort[0] = 0.2;      // N·m at the motor
  v.actuator_velocity[0] = 100.0;  // rad/s at the motor
  v.actuator_position[0] = 5.0 * M_PI;
  actuatorToJoint(t, v);
  EXPECT_NEAR(v.joint_effort[0], 10.0, kTol);
  EXPECT_NEAR(v.joint_velocity[0], 2.0, kTol);
  EXPECT_NEAR(v.joint_position[0], M_PI / 10.0, kTol);
}

TEST(SimpleTransmission, NegativeReductionReversesDirection) {
  const st::SimpleTransmission t(-2.0);
  Values v(1);
  v.setActuators(1.0, 0.0);
  actuatorToJoint(t, v);
  EXPECT_NEAR(v.joint_effort[0], -2.0, kTol);
  EXPECT_NEAR(v.joint_velocity[0], -0.5, kTol);
  EXPECT_NEAR(v.joint_position[0], -0.5, kTol);
}

// --- Differential: a = [10, −20], j = [−2, 4], o = [−2, 4], actuator [3, 5].

TEST(DifferentialTransmission, ReferenceCaseActuatorToJoint) {
  const st::DifferentialTransmission t({10.0, -20.0}, {-2.0, 4.0}, {-2.0, 4.0});
  EXPECT_EQ(t.numActuators(), 2u);
  EXPECT_EQ(t.numJoints(), 2u);
  Values v(2);
  v.setActuators(3.0, 5.0);
  actuatorToJoint(t, v);
  EXPECT_NEAR(v.joint_effort[0], 140.0, kTol);
  EXPECT_NEAR(v.joint_effort[1], 520.0, kTol);
  EXPECT_NEAR(v.joint_velocity[0], -0.0125, kTol);
  EXPECT_NEAR(v.joint_velocity[1], 0.06875, kTol);
  EXPECT_NEAR(v.joint_position[0], -2.0125, kTol);
  EXPECT_NEAR(v.joint_position[1], 4.06875, kTol);
}

TEST(DifferentialTransmission, ReferenceCaseJointToActuator) {
  const st::DifferentialTransmission t({10.0, -20.0}, {-2.0, 4.0}, {-2.0, 4.0});
  Values v(2);
  v.joint_effort = {140.0, 520.0};
  v.joint_velocity = {-0.0125, 0.06875};
  v.joint_position = {-2.0125, 4.06875};
  jointToActuator(t, v);
  for (const auto* quantity : {&v.actuator_effort, &v.actuator_velocity, &v.actuator_position}) {
    EXPECT_NEAR((*quantity)[0], 3.0, kTol);
    EXPECT_NEAR((*quantity)[1], 5.0, kTol);
  }
}

// --- Four-bar: same a, j, o, actuator [3, 5].

TEST(FourBarLinkageTransmission, ReferenceCaseActuatorToJoint) {
  const st::FourBarLinkageTransmission t({10.0, -20.0}, {-2.0, 4.0}, {-2.0, 4.0});
  EXPECT_EQ(t.numActuators(), 2u);
  EXPECT_EQ(t.numJoints(), 2u);
  Values v(2);
  v.setActuators(3.0, 5.0);
  actuatorToJoint(t, v);
  EXPECT_NEAR(v.joint_effort[0], -60.0, kTol);
  EXPECT_NEAR(v.joint_effort[1], -160.0, kTol);
  EXPECT_NEAR(v.joint_velocity[0], -0.15, kTol);
  EXPECT_NEAR(v.joint_velocity[1], -0.025, kTol);
  EXPECT_NEAR(v.joint_position[0], -2.15, kTol);
  EXPECT_NEAR(v.joint_position[1], 3.975, kTol);
}

TEST(FourBarLinkageTransmission, ReferenceCaseJointToActuator) {
  const st::FourBarLinkageTransmission t({10.0, -20.0}, {-2.0, 4.0}, {-2.0, 4.0});
  Values v(2);
  v.joint_effort = {-60.0, -160.0};
  v.joint_velocity = {-0.15, -0.025};
  v.joint_position = {-2.15, 3.975};
  jointToActuator(t, v);
  for (const auto* quantity : {&v.actuator_effort, &v.actuator_velocity, &v.actuator_position}) {
    EXPECT_NEAR((*quantity)[0], 3.0, kTol);
    EXPECT_NEAR((*quantity)[1], 5.0, kTol);
  }
}

// --- Round trips: actuator → joint → actuator is the identity, for every
// quantity, with random reductions, offsets and values.

namespace {

enum class Kind { simple, differential, four_bar };

// Reductions in realistic ranges: motor gears up to 100:1 either way round,
// joint-side reductions near 1. (With both near 100 the product scales the
// rounding of the joint offset past 1e-12 on its own.)
std::unique_ptr<st::Transmission> randomTransmission(Kind kind, std::mt19937& rng) {
  std::uniform_real_distribution<double> actuator_magnitude(0.1, 100.0);
  std::uniform_real_distribution<double> joint_magnitude(0.5, 2.0);
  std::uniform_real_distribution<double> offset(-3.0, 3.0);
  std::bernoulli_distribution negative(0.3);
  auto sign = [&] { return negative(rng) ? -1.0 : 1.0; };
  auto actuator = [&] { return sign() * actuator_magnitude(rng); };
  auto joint = [&] { return sign() * joint_magnitude(rng); };
  switch (kind) {
    case Kind::simple:
      return std::make_unique<st::SimpleTransmission>(actuator(), offset(rng));
    case Kind::differential:
      return std::make_unique<st::DifferentialTransmission>(std::array{actuator(), actuator()},
                                                            std::array{joint(), joint()},
                                                            std::array{offset(rng), offset(rng)});
    case Kind::four_bar:
      return std::make_unique<st::FourBarLinkageTransmission>(std::array{actuator(), actuator()},
                                                              std::array{joint(), joint()},
                                                              std::array{offset(rng), offset(rng)});
  }
  return nullptr;
}

void expectRoundTripsAreIdentity(Kind kind) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto t = randomTransmission(kind, rng);
    const std::size_t n = t->numActuators();
    Values v(n);
    std::array<double, 2> position{}, velocity{}, effort{};
    for (std::size_t i = 0; i < n; ++i) {
      position[i] = v.actuator_position[i] = value(rng);
      velocity[i] = v.actuator_velocity[i] = value(rng);
      effort[i] = v.actuator_effort[i] = value(rng);
    }
    actuatorToJoint(*t, v);
    v.actuator_position = v.actuator_velocity = v.actuator_effort = {NAN, NAN};
    jointToActuator(*t, v);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(v.actuator_position[i], position[i], kTol)
          << "trial " << trial << " actuator " << i;
      EXPECT_NEAR(v.actuator_velocity[i], velocity[i], kTol)
          << "trial " << trial << " actuator " << i;
      EXPECT_NEAR(v.actuator_effort[i], effort[i], kTol) << "trial " << trial << " actuator " << i;
    }

    // And joint → actuator → joint.
    std::array<double, 2> joint_position{}, joint_velocity{}, joint_effort{};
    for (std::size_t i = 0; i < n; ++i) {
      joint_position[i] = v.joint_position[i] = value(rng);
      joint_velocity[i] = v.joint_velocity[i] = value(rng);
      joint_effort[i] = v.joint_effort[i] = value(rng);
    }
    jointToActuator(*t, v);
    v.joint_position = v.joint_velocity = v.joint_effort = {NAN, NAN};
    actuatorToJoint(*t, v);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_NEAR(v.joint_position[i], joint_position[i], kTol);
      EXPECT_NEAR(v.joint_velocity[i], joint_velocity[i], kTol);
      EXPECT_NEAR(v.joint_effort[i], joint_effort[i], kTol);
    }
  }
}

}  // namespace

TEST(SimpleTransmission, RoundTripsAreIdentity) { expectRoundTripsAreIdentity(Kind::simple); }
TEST(DifferentialTransmission, RoundTripsAreIdentity) {
  expectRoundTripsAreIdentity(Kind::differential);
}
TEST(FourBarLinkageTransmission, RoundTripsAreIdentity) {
  expectRoundTripsAreIdentity(Kind::four_bar);
}

// --- Zero reductions are rejected, naming which one.

namespace {
template <class F>
std::string configErrorMessage(F&& make) {
  try {
    make();
  } catch (const servoloop::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError";
  return {};
}
}  // namespace

TEST(SimpleTransmission, RejectsZeroReduction) {
  const std::string message = configErrorMessage([] { st::SimpleTransmission t(0.0, 1.0); });
  EXPECT_NE(message.find("SimpleTransmission"), std::string::npos) << message;
  EXPECT_NE(message.find("reduction"), std::string::npos) << message;
  EXPECT_NE(message.find("non-zero"), std::string::npos) << message;
}

TEST(SimpleTransmission, RejectsNonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(st::SimpleTransmission{nan}, servoloop::ConfigError);
  EXPECT_THROW(st::SimpleTransmission{inf}, servoloop::ConfigError);
  EXPECT_THROW((st::SimpleTransmission{1.0, nan}), servoloop::ConfigError);
}

TEST(DifferentialTransmission, RejectsEachZeroReductionByName) {
  const std::array<std::string, 4> names = {"actuator_reductions[0]", "actuator_reductions[1]",
                                            "joint_reductions[0]", "joint_reductions[1]"};
  for (std::size_t zero = 0; zero < 4; ++zero) {
    std::array<double, 4> r = {2.0, 3.0, 4.0, 5.0};
    r[zero] = 0.0;
    const std::string message = configErrorMessage([&] {
      st::DifferentialTransmission t({r[0], r[1]}, {r[2], r[3]});
    });
    EXPECT_NE(message.find("DifferentialTransmission"), std::string::npos) << message;
    EXPECT_NE(message.find(names[zero]), std::string::npos) << message;
  }
}

TEST(FourBarLinkageTransmission, RejectsEachZeroReductionByName) {
  const std::array<std::string, 4> names = {"actuator_reductions[0]", "actuator_reductions[1]",
                                            "joint_reductions[0]", "joint_reductions[1]"};
  for (std::size_t zero = 0; zero < 4; ++zero) {
    std::array<double, 4> r = {2.0, 3.0, 4.0, 5.0};
    r[zero] = 0.0;
    const std::string message = configErrorMessage([&] {
      st::FourBarLinkageTransmission t({r[0], r[1]}, {r[2], r[3]});
    });
    EXPECT_NE(message.find("FourBarLinkageTransmission"), std::string::npos) << message;
    EXPECT_NE(message.find(names[zero]), std::string::npos) << message;
  }
}
