// The robot namespace rule of CLI.md: the URDF's gazebo_ros_control
// robotNamespace wins, else the launch file's namespace, else /<robot name>.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/core/errors.hpp"

namespace {

using servoloop::node::resolveRobotNamespace;
using servoloop::node::urdfRobotNamespace;

std::string urdfWithPlugin(const std::string& plugin) {
  return "<robot name='arm'><link name='base'/>" + plugin + "</robot>";
}

TEST(RobotNamespace, SeedUrdfGivesOneDofRobot) {
  std::ifstream in(std::string(SERVOLOOP_SOURCE_DIR) + "/robots/one_dof/minimal_robot_description_w_jnt_ctl.urdf");
  std::stringstream xml;
  xml << in.rdbuf();
  EXPECT_EQ(urdfRobotNamespace(xml.str(), "seed.urdf"), "/one_DOF_robot");
  // The URDF wins over the launch file's namespace.
  EXPECT_EQ(resolveRobotNamespace(xml.str(), "seed.urdf", "/other", "one_DOF_robot"), "/one_DOF_robot");
}

TEST(RobotNamespace, UrdfWinsOverLaunchFile) {
  const std::string xml = urdfWithPlugin(
      "<gazebo><plugin name='gazebo_ros_control' filename='libgazebo_ros_control.so'>"
      "<robotNamespace> /left_arm </robotNamespace></plugin></gazebo>");
  EXPECT_EQ(resolveRobotNamespace(xml, "arm.urdf", "/right_arm", "arm"), "/left_arm");
  // Said, so that a user commanding /right_arm/... knows why nothing moves.
  const std::string warning = servoloop::node::ignoredLaunchNamespace(xml, "arm.urdf", "/right_arm");
  EXPECT_NE(warning.find("arm.urdf: the robot's namespace is '/left_arm'"), std::string::npos) << warning;
  EXPECT_NE(warning.find("the launch file's namespace '/right_arm' is not used"), std::string::npos) << warning;
  // The same namespace written differently, none, or a ROS launch file's root: nothing to say.
  EXPECT_EQ(servoloop::node::ignoredLaunchNamespace(xml, "arm.urdf", "left_arm/"), "");
  EXPECT_EQ(servoloop::node::ignoredLaunchNamespace(xml, "arm.urdf", ""), "");
  EXPECT_EQ(servoloop::node::ignoredLaunchNamespace(xml, "arm.urdf", "/"), "");
  EXPECT_EQ(servoloop::node::ignoredLaunchNamespace(urdfWithPlugin(""), "arm.urdf", "/right_arm"), "");
}

TEST(RobotNamespace, LaunchFileNamespaceWhenUrdfHasNone) {
  const std::string xml = urdfWithPlugin("");
  EXPECT_EQ(urdfRobotNamespace(xml, "arm.urdf"), "");
  EXPECT_EQ(resolveRobotNamespace(xml, "arm.urdf", "/right_arm", "arm"), "/right_arm");
  EXPECT_EQ(resolveRobotNamespace(xml, "arm.urdf", "right_arm/", "arm"), "/right_arm");
}

TEST(RobotNamespace, RobotNameWhenNeitherGivesOne) {
  EXPECT_EQ(resolveRobotNamespace(urdfWithPlugin(""), "arm.urdf", "", "my_arm"), "/my_arm");
}

TEST(RobotNamespace, OtherPluginsAndEmptyNamespacesAreIgnored) {
  const std::string xml = urdfWithPlugin(
      "<gazebo><plugin filename='libgazebo_ros_camera.so'><robotNamespace>/camera</robotNamespace></plugin>"
      "<plugin filename='libgazebo_ros_control.so'><robotNamespace>  </robotNamespace></plugin></gazebo>");
  EXPECT_EQ(urdfRobotNamespace(xml, "arm.urdf"), "");
  EXPECT_EQ(resolveRobotNamespace(xml, "arm.urdf", "", "arm"), "/arm");
}

TEST(RobotNamespace, NotXmlNamesTheFile) {
  try {
    urdfRobotNamespace("<robot", "broken.urdf");
    FAIL() << "no error";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.urdf: not valid XML"), std::string::npos) << e.what();
  }
}

}  // namespace
