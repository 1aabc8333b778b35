// simulatableUrdf: a moving link without mass is left out with what hangs
// below it (Gazebo's URDF import does the same), with one warning; and
// parseRobotModel leaves non-URDF elements inside links alone.
#include "servoloop/description/simulatable_urdf.hpp"

#include <string>

#include <gtest/gtest.h>

#include "log_capture.hpp"
#include "servoloop/description/robot_model.hpp"

namespace servoloop {
namespace {

const std::string kInertial = R"(<inertial><mass value="1"/>
  <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>)";

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child) {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent + "\"/><child link=\"" +
         child + "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
}

// world -> base (fixed) -> arm (j_arm) -> sensor (j_sensor, no inertial)
//   -> tip (j_tip, has mass, below the massless link) ; base -> wheel (j_wheel)
std::string robotWithMasslessSensor(const std::string& sensor_inertial) {
  return R"(<?xml version="1.0"?><robot name="r"><link name="world"/>
    <link name="base">)" + kInertial + R"(</link>
    <link name="arm">)" + kInertial + R"(</link>
    <link name="sensor">)" + sensor_inertial + R"(</link>
    <link name="tip">)" + kInertial + R"(</link>
    <link name="wheel">)" + kInertial + "</link>" +
         joint("fix", "fixed", "world", "base") + joint("j_arm", "revolute", "base", "arm") +
         joint("j_sensor", "revolute", "arm", "sensor") + joint("j_tip", "revolute", "sensor", "tip") +
         joint("j_wheel", "continuous", "base", "wheel") + R"(
    <transmission name="t_tip"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j_tip"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
      <actuator name="m_tip"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
    <transmission name="t_arm"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j_arm"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
      <actuator name="m_arm"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
    </robot>)";
}

TEST(SimulatableUrdf, LeavesOutAMasslessMovingLinkWithWhatHangsBelowIt) {
  test::LogCapture log;
  const SimulatableUrdf result = simulatableUrdf(robotWithMasslessSensor(""), "r.urdf");
  EXPECT_EQ(result.skipped_links, (std::vector<std::string>{"sensor", "tip"}));
  EXPECT_EQ(result.skipped_joints, (std::vector<std::string>{"j_sensor", "j_tip"}));
  EXPECT_EQ(result.skipped_transmissions, std::vector<std::string>{"t_tip"});
  EXPECT_EQ(log.count("link 'sensor' (moved by joint 'j_sensor') has no <inertial>"), 1u) << log.text();
  EXPECT_NE(log.text().find("links 'tip'"), std::string::npos) << log.text();
  EXPECT_NE(log.text().find("Add <inertial>"), std::string::npos) << log.text();

  // What is left is a robot the strict loader takes: base, arm, wheel.
  const auto model = parseRobotModel(result.xml, "r.urdf");
  EXPECT_TRUE(model->getLink("arm"));
  EXPECT_TRUE(model->getLink("wheel"));
  EXPECT_FALSE(model->getLink("sensor"));
  EXPECT_FALSE(model->getLink("tip"));
  EXPECT_FALSE(model->getJoint("j_tip"));
  EXPECT_NE(result.xml.find("t_arm"), std::string::npos);
  EXPECT_EQ(result.xml.find("t_tip"), std::string::npos);
}

TEST(SimulatableUrdf, ZeroMassCountsAsNoMass) {
  test::LogCapture log;
  const SimulatableUrdf result = simulatableUrdf(
      robotWithMasslessSensor(R"(<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>)"),
      "r.urdf");
  EXPECT_EQ(result.skipped_links, (std::vector<std::string>{"sensor", "tip"}));
  EXPECT_EQ(log.count("has no mass (<inertial><mass> <= 0)"), 1u) << log.text();
}

// A massless link carrying a massive link on a fixed joint is one rigid body
// with that mass, as Gazebo lumps fixed joints: nothing is left out.
TEST(SimulatableUrdf, KeepsAMasslessLinkWhoseFixedChildrenHaveMass) {
  const std::string xml = R"(<?xml version="1.0"?><robot name="r"><link name="world"/>
    <link name="hub"/><link name="rim">)" + kInertial + "</link>" +
                          joint("spin", "continuous", "world", "hub") + joint("weld", "fixed", "hub", "rim") +
                          "</robot>";
  const SimulatableUrdf result = simulatableUrdf(xml, "r.urdf");
  EXPECT_TRUE(result.skipped_links.empty());
  EXPECT_EQ(result.xml, xml);  // unchanged, byte for byte
  EXPECT_NO_THROW(parseRobotModel(result.xml, "r.urdf"));
}

TEST(SimulatableUrdf, LeavesAMalformedDescriptionForTheLoaderToReport) {
  const std::string not_a_tree = R"(<robot name="r"><link name="a"/><link name="b"/></robot>)";
  EXPECT_EQ(simulatableUrdf(not_a_tree, "r.urdf").xml, not_a_tree);
  EXPECT_EQ(simulatableUrdf("<robot", "r.urdf").xml, "<robot");
}

// ROS's parser ignores elements that are not URDF's (PR2 has
// <verbose value="Yes"/> in its links); numbers are checked only where URDF
// has numbers.
TEST(SimulatableUrdf, NonUrdfElementsInsideALinkAreLeftAlone) {
  const std::string xml = R"(<?xml version="1.0"?><robot name="r"><link name="world"/>
    <link name="arm">)" + kInertial + R"(<verbose value="Yes"/><sensor_hint value="camera"/></link>)" +
                          joint("j", "revolute", "world", "arm") + "</robot>";
  EXPECT_NO_THROW(parseRobotModel(xml, "pr2_like.urdf"));
}

}  // namespace
}  // namespace servoloop
