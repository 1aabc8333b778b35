// Joint limits from URDF and YAML (ros_control_semantics.md "Joint limits"):
// the seed robots, inline URDFs, YAML overrides and bad YAML.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_limits_loader.hpp"
#include "servoloop/hardware_interface/joint_limits_urdf.hpp"
#include "servoloop/hardware_interface/joint_limits_yaml.hpp"
#include "expect_contains.hpp"

namespace hi = servoloop::hardware_interface;

namespace {

const std::string kSeedDir = std::string(SERVOLOOP_SEED_DIR) + "/";

urdf::ModelInterfaceSharedPtr loadSeed(const std::string& file) {
  auto model = urdf::parseURDFFile(kSeedDir + file);
  if (!model) throw std::runtime_error("cannot parse " + file);
  return model;
}

// A one-joint robot; joint_xml is the <joint> element.
urdf::ModelInterfaceSharedPtr oneJointRobot(const std::string& joint_xml) {
  const std::string xml = R"(<robot name="r"><link name="a"/><link name="b"/>)" + joint_xml + "</robot>";
  auto model = urdf::parseURDF(xml);
  if (!model) throw std::runtime_error("cannot parse inline URDF");
  return model;
}

// The seed's joint1 limits: position [0, 2], velocity 0.5, effort 10.
hi::JointLimits seedJoint1Limits() {
  hi::JointLimits limits;
  hi::getJointLimits(*loadSeed("minimal_robot_description_w_jnt_ctl.urdf")->getJoint("joint1"), limits);
  return limits;
}

template <class F>
std::string configErrorOf(F&& f) {
  try {
    f();
  } catch (const servoloop::ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

}  // namespace

// --- URDF ---------------------------------------------------------------------

TEST(JointLimitsUrdf, SeedRevoluteJoint) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  hi::JointLimits limits;
  ASSERT_TRUE(hi::getJointLimits(*model->getJoint("joint1"), limits));
  EXPECT_TRUE(limits.has_position_limits);
  EXPECT_EQ(limits.min_position, 0.0);
  EXPECT_EQ(limits.max_position, 2.0);
  EXPECT_TRUE(limits.has_velocity_limits);
  EXPECT_EQ(limits.max_velocity, 0.5);
  EXPECT_TRUE(limits.has_effort_limits);
  EXPECT_EQ(limits.max_effort, 10.0);
  EXPECT_FALSE(limits.has_acceleration_limits);
  EXPECT_FALSE(limits.angle_wraparound);

  hi::SoftJointLimits soft;
  EXPECT_FALSE(hi::getSoftJointLimits(*model->getJoint("joint1"), soft));
}

TEST(JointLimitsUrdf, SeedContinuousJointWraps) {
  auto model = loadSeed("minimal_robot_description.urdf");
  hi::JointLimits limits;
  ASSERT_TRUE(hi::getJointLimits(*model->getJoint("joint1"), limits));
  EXPECT_TRUE(limits.angle_wraparound);
  EXPECT_FALSE(limits.has_position_limits);
  // The seed's continuous joint has no <limit>: nothing else is limited.
  EXPECT_FALSE(limits.has_velocity_limits);
  EXPECT_FALSE(limits.has_effort_limits);
  EXPECT_FALSE(limits.has_acceleration_limits);
}

TEST(JointLimitsUrdf, FixedJointGivesNothing) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  hi::JointLimits limits;
  limits.max_effort = 42.0;
  EXPECT_FALSE(hi::getJointLimits(*model->getJoint("glue_robot_to_world"), limits));
  EXPECT_EQ(limits.max_effort, 42.0);
  EXPECT_FALSE(limits.has_effort_limits);
}

TEST(JointLimitsUrdf, ContinuousJointWithLimitHasVelocityAndEffortButNoRange) {
  auto model = oneJointRobot(R"(<joint name="j" type="continuous"><parent link="a"/><child link="b"/>
      <limit effort="3" velocity="7" lower="-1" upper="1"/></joint>)");
  hi::JointLimits limits;
  ASSERT_TRUE(hi::getJointLimits(*model->getJoint("j"), limits));
  EXPECT_FALSE(limits.has_position_limits);
  EXPECT_TRUE(limits.angle_wraparound);
  EXPECT_EQ(limits.max_velocity, 7.0);
  EXPECT_EQ(limits.max_effort, 3.0);
}

TEST(JointLimitsUrdf, PrismaticJointWithSafetyController) {
  auto model = oneJointRobot(R"(<joint name="slider" type="prismatic"><parent link="a"/><child link="b"/>
      <limit effort="100" velocity="0.2" lower="-0.3" upper="0.4"/>
      <safety_controller soft_lower_limit="-0.25" soft_upper_limit="0.35" k_position="50" k_velocity="8"/>
      </joint>)");
  const urdf::Joint& joint = *model->getJoint("slider");
  hi::JointLimits limits;
  ASSERT_TRUE(hi::getJointLimits(joint, limits));
  EXPECT_TRUE(limits.has_position_limits);
  EXPECT_EQ(limits.min_position, -0.3);
  EXPECT_EQ(limits.max_position, 0.4);
  EXPECT_EQ(limits.max_velocity, 0.2);
  EXPECT_EQ(limits.max_effort, 100.0);
  EXPECT_FALSE(limits.angle_wraparound);

  hi::SoftJointLimits soft;
  ASSERT_TRUE(hi::getSoftJointLimits(joint, soft));
  EXPECT_EQ(soft.min_position, -0.25);
  EXPECT_EQ(soft.max_position, 0.35);
  EXPECT_EQ(soft.k_position, 50.0);
  EXPECT_EQ(soft.k_velocity, 8.0);
}

// --- YAML overrides -----------------------------------------------------------

TEST(JointLimitsYaml, UndefinedNodeLeavesLimits) {
  hi::JointLimits limits = seedJoint1Limits();
  YAML::Node root = YAML::Load("{other: 1}");
  EXPECT_FALSE(hi::getJointLimits(root["joint1"], "joint1", limits));
  EXPECT_EQ(limits.max_velocity, 0.5);
}

TEST(JointLimitsYaml, GroupsOverrideTheUrdf) {
  hi::JointLimits limits = seedJoint1Limits();
  const YAML::Node node = YAML::Load(R"(
    has_position_limits: true
    min_position: 0.25
    max_position: 1.5
    has_velocity_limits: true
    max_velocity: 0.25
    has_acceleration_limits: true
    max_acceleration: 4
    has_effort_limits: false
  )");
  ASSERT_TRUE(hi::getJointLimits(node, "joint1", limits));
  EXPECT_TRUE(limits.has_position_limits);
  EXPECT_EQ(limits.min_position, 0.25);
  EXPECT_EQ(limits.max_position, 1.5);
  EXPECT_EQ(limits.max_velocity, 0.25);
  EXPECT_TRUE(limits.has_acceleration_limits);
  EXPECT_EQ(limits.max_acceleration, 4.0);
  EXPECT_FALSE(limits.has_effort_limits);
}

TEST(JointLimitsYaml, ValueWithoutItsHasKeyIsIgnored) {
  hi::JointLimits limits = seedJoint1Limits();
  ASSERT_TRUE(hi::getJointLimits(YAML::Load("{max_velocity: 9, max_effort: 1, min_position: -5}"),
                                 "joint1", limits));
  EXPECT_EQ(limits.max_velocity, 0.5);
  EXPECT_EQ(limits.max_effort, 10.0);
  EXPECT_EQ(limits.min_position, 0.0);
}

TEST(JointLimitsYaml, SwitchedOnGroupKeepsUrdfValuesNotGiven) {
  hi::JointLimits limits = seedJoint1Limits();
  ASSERT_TRUE(hi::getJointLimits(YAML::Load("{has_position_limits: true, max_position: 1.0}"), "joint1",
                                 limits));
  EXPECT_EQ(limits.min_position, 0.0);
  EXPECT_EQ(limits.max_position, 1.0);
}

TEST(JointLimitsYaml, SwitchedOnGroupWithoutAnyValueIsAnError) {
  hi::JointLimits limits;  // nothing from a URDF
  const std::string message = configErrorOf([&] {
    hi::getJointLimits(YAML::Load("{has_acceleration_limits: true}"), "joint1", limits);
  });
  EXPECT_CONTAINS(message, "joint_limits/joint1");
  EXPECT_CONTAINS(message, "has_acceleration_limits is true but max_acceleration is missing");
  EXPECT_FALSE(limits.has_acceleration_limits);
}

TEST(JointLimitsYaml, PositionLimitsOffWithWraparound) {
  hi::JointLimits limits = seedJoint1Limits();
  ASSERT_TRUE(hi::getJointLimits(YAML::Load("{has_position_limits: false, angle_wraparound: true}"),
                                 "joint1", limits));
  EXPECT_FALSE(limits.has_position_limits);
  EXPECT_TRUE(limits.angle_wraparound);
}

TEST(JointLimitsYaml, PositionLimitsOnAContinuousJointEndWraparound) {
  hi::JointLimits limits;
  limits.angle_wraparound = true;
  ASSERT_TRUE(hi::getJointLimits(
      YAML::Load("{has_position_limits: true, min_position: -3, max_position: 3}"), "j", limits));
  EXPECT_TRUE(limits.has_position_limits);
  EXPECT_FALSE(limits.angle_wraparound);
}

TEST(JointLimitsYaml, WrongTypesNameJointKeyAndType) {
  struct Case {
    const char* yaml;
    const char* key;
    const char* expected;
    const char* got;
  };
  const Case cases[] = {
      {"{has_velocity_limits: true, max_velocity: fast}", "joint_limits/joint1/max_velocity", "a number",
       "'fast'"},
      {"{has_velocity_limits: maybe}", "joint_limits/joint1/has_velocity_limits", "a boolean", "'maybe'"},
      {"{has_effort_limits: true, max_effort: [1, 2]}", "joint_limits/joint1/max_effort", "a number",
       "a list"},
      {"{has_position_limits: true, min_position: {a: 1}, max_position: 1}",
       "joint_limits/joint1/min_position", "a number", "a map"},
      {"{has_soft_limits: true, k_position: x, k_velocity: 1, soft_lower_limit: 0, soft_upper_limit: 1}",
       "joint_limits/joint1/k_position", "a number", "'x'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.yaml);
    hi::JointLimits limits = seedJoint1Limits();
    std::optional<hi::SoftJointLimits> soft;
    const YAML::Node node = YAML::Load(c.yaml);
    const std::string message = configErrorOf([&] {
      hi::getJointLimits(node, "joint1", limits);
      hi::getSoftJointLimits(node, "joint1", soft);
    });
    EXPECT_CONTAINS(message, c.key);
    EXPECT_CONTAINS(message, std::string("expected ") + c.expected);
    EXPECT_CONTAINS(message, std::string("got ") + c.got);
    // A failed read leaves the limits as they were.
    EXPECT_EQ(limits.max_velocity, 0.5);
    EXPECT_EQ(limits.max_effort, 10.0);
  }
}

TEST(JointLimitsYaml, JointEntryMustBeAMap) {
  hi::JointLimits limits;
  const std::string message =
      configErrorOf([&] { hi::getJointLimits(YAML::Load("3.0"), "joint1", limits); });
  EXPECT_CONTAINS(message, "joint_limits/joint1: expected a map");
}

TEST(JointLimitsYaml, SoftLimits) {
  const YAML::Node node = YAML::Load(
      "{has_soft_limits: true, k_position: 100, k_velocity: 20, soft_lower_limit: 0.1, "
      "soft_upper_limit: 1.9}");
  std::optional<hi::SoftJointLimits> soft;
  ASSERT_TRUE(hi::getSoftJointLimits(node, "joint1", soft));
  ASSERT_TRUE(soft.has_value());
  EXPECT_EQ(soft->k_position, 100.0);
  EXPECT_EQ(soft->k_velocity, 20.0);
  EXPECT_EQ(soft->min_position, 0.1);
  EXPECT_EQ(soft->max_position, 1.9);

  // Partial override of existing (URDF) soft limits.
  ASSERT_TRUE(hi::getSoftJointLimits(YAML::Load("{has_soft_limits: true, k_velocity: 5}"), "joint1", soft));
  EXPECT_EQ(soft->k_velocity, 5.0);
  EXPECT_EQ(soft->k_position, 100.0);

  // No has_soft_limits: unchanged, even with values next to it.
  ASSERT_TRUE(hi::getSoftJointLimits(YAML::Load("{k_velocity: 7}"), "joint1", soft));
  EXPECT_EQ(soft->k_velocity, 5.0);

  // has_soft_limits: false removes them.
  EXPECT_FALSE(hi::getSoftJointLimits(YAML::Load("{has_soft_limits: false}"), "joint1", soft));
  EXPECT_FALSE(soft.has_value());

  // Switched on without values and nothing to take them from.
  const std::string message = configErrorOf([&] {
    hi::getSoftJointLimits(YAML::Load("{has_soft_limits: true, k_position: 1}"), "joint1", soft);
  });
  EXPECT_CONTAINS(message, "has_soft_limits is true but k_velocity is missing");
}

// --- Whole robot --------------------------------------------------------------

TEST(JointLimitsLoader, SeedRobotWithSeedParamsUsesTheUrdf) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  const YAML::Node params = YAML::LoadFile(kSeedDir + "control_config/one_dof_ctl_params.yaml");
  const hi::RobotJointLimits all = hi::loadRobotJointLimits(*model, params["one_DOF_robot"]);
  ASSERT_EQ(all.size(), 1u);  // the fixed joint has no entry
  const hi::JointLimitsConfig& joint1 = all.at("joint1");
  EXPECT_EQ(joint1.limits.max_position, 2.0);
  EXPECT_EQ(joint1.limits.max_velocity, 0.5);
  EXPECT_EQ(joint1.limits.max_effort, 10.0);
  EXPECT_FALSE(joint1.soft_limits.has_value());
}

TEST(JointLimitsLoader, YamlUnderTheRobotNamespaceOverrides) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  const YAML::Node ns = YAML::Load(R"(
    joint_limits:
      joint1:
        has_velocity_limits: true
        max_velocity: 0.3
        has_soft_limits: true
        k_position: 10
        k_velocity: 2
        soft_lower_limit: 0.1
        soft_upper_limit: 1.9
  )");
  const hi::RobotJointLimits all = hi::loadRobotJointLimits(*model, ns);
  const hi::JointLimitsConfig& joint1 = all.at("joint1");
  EXPECT_EQ(joint1.limits.max_velocity, 0.3);
  EXPECT_EQ(joint1.limits.max_effort, 10.0);
  ASSERT_TRUE(joint1.soft_limits.has_value());
  EXPECT_EQ(joint1.soft_limits->max_position, 1.9);
}

TEST(JointLimitsLoader, ContinuousSeedJoint) {
  auto model = loadSeed("minimal_robot_description.urdf");
  const hi::RobotJointLimits all = hi::loadRobotJointLimits(*model, YAML::Node());
  ASSERT_EQ(all.count("joint1"), 1u);
  EXPECT_TRUE(all.at("joint1").limits.angle_wraparound);
}

TEST(JointLimitsLoader, UnknownJointNamesTheFileAndTheJoints) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  const YAML::Node ns = YAML::Load("{joint_limits: {joint_1: {has_velocity_limits: false}}}");
  const std::string message =
      configErrorOf([&] { hi::loadRobotJointLimits(*model, ns, "one_dof_ctl_params.yaml"); });
  EXPECT_CONTAINS(message, "one_dof_ctl_params.yaml: joint_limits/joint_1");
  EXPECT_CONTAINS(message, "it has: joint1");
}

TEST(JointLimitsLoader, InvertedOrNegativeLimitsAreRefused) {
  auto model = loadSeed("minimal_robot_description_w_jnt_ctl.urdf");
  std::string message = configErrorOf([&] {
    hi::loadRobotJointLimits(
        *model, YAML::Load("{joint_limits: {joint1: {has_position_limits: true, min_position: 3}}}"));
  });
  EXPECT_CONTAINS(message, "joint 'joint1': min_position 3 is above max_position 2");

  message = configErrorOf([&] {
    hi::loadRobotJointLimits(
        *model, YAML::Load("{joint_limits: {joint1: {has_effort_limits: true, max_effort: -1.5}}}"));
  });
  EXPECT_CONTAINS(message, "joint 'joint1': max_effort is -1.5");
}
