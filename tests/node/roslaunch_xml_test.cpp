// ROS launch files: the seed's two .launch files read to the same robots as
// their YAML counterparts, each roslaunch construct a robot launch uses, and
// one error naming the file and line per mistake.
#include "servoloop/node/roslaunch_xml.hpp"

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/node/launch_file.hpp"
#include "temp_dir.hpp"
#include "expect_contains.hpp"

namespace servoloop::node {
namespace {

namespace fs = std::filesystem;
using servoloop::testing::TempDir;
using servoloop::testing::writeFile;

const fs::path kOneDof = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";

// A one-joint robot; `extra` goes inside <robot>.
std::string robotUrdf(const std::string& name, const std::string& extra = "") {
  return R"~(<robot name=")~" + name + R"~("><link name="world"/><link name="arm"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
    <joint name="hinge" type="revolute"><parent link="world"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="5" velocity="2"/></joint>)~" +
         extra + "</robot>";
}

TEST(RoslaunchXml, SeedLaunchWithControllersReadsAsItsYamlCounterpart) {
  const LaunchFile xml = loadLaunchFile(kOneDof / "minimal_robot_w_jnt_ctl.launch");
  const LaunchFile yaml = loadLaunchFile(kOneDof / "one_dof_w_jnt_ctl.launch.yaml");
  ASSERT_EQ(xml.robots.size(), 1u);
  ASSERT_EQ(yaml.robots.size(), 1u);
  const RobotSpec& a = xml.robots[0];
  const RobotSpec& b = yaml.robots[0];
  EXPECT_EQ(fs::canonical(a.urdf), fs::canonical(b.urdf));
  EXPECT_EQ(a.model, "one_DOF_robot");
  EXPECT_EQ(a.controllers, b.controllers);
  EXPECT_TRUE(a.stopped_controllers.empty());
  ASSERT_EQ(a.params.size(), 1u);
  EXPECT_EQ(fs::canonical(a.params[0].file), fs::canonical(b.params[0].file));
  EXPECT_EQ(a.params[0].ns, "/");
  EXPECT_EQ(xml.world.backend, yaml.world.backend);
  EXPECT_EQ(xml.world.ground_plane, yaml.world.ground_plane);
}

TEST(RoslaunchXml, SeedLaunchWithoutControllersSpawnsTheBareRobot) {
  const LaunchFile xml = loadLaunchFile(kOneDof / "minimal_robot_description.launch");
  ASSERT_EQ(xml.robots.size(), 1u);
  EXPECT_EQ(fs::canonical(xml.robots[0].urdf), fs::canonical(kOneDof / "minimal_robot_description.urdf"));
  EXPECT_EQ(xml.robots[0].model, "one_DOF_robot");
  EXPECT_TRUE(xml.robots[0].controllers.empty());
  // spawn_model at the root: Gazebo gives the robot the root namespace.
  EXPECT_EQ(xml.robots[0].robot_namespace, "/");
}

// A bring-up as ROS users write it: arguments, an included world and an
// included description file, a group namespace, xacro with arguments,
// parameters of every kind, a spawn pose and start positions, spawners.
class RoslaunchProject : public ::testing::Test {
 protected:
  void SetUp() override {
    writeFile(dir_.path() / "arm_description/package.xml", "<package><name>arm_description</name></package>");
    writeFile(dir_.path() / "arm_description/urdf/arm.urdf.xacro",
              R"~(<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:arg name="prefix" default=""/>
                 <link name="world"/><link name="$(arg prefix)arm"><inertial><mass value="1"/>
                 <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
                 <joint name="$(arg prefix)hinge" type="revolute"><parent link="world"/><child link="$(arg prefix)arm"/>
                 <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint></robot>)~");
    writeFile(dir_.path() / "arm_description/launch/description.launch", R"~(<launch>
        <arg name="prefix"/>
        <param name="robot_description" command="$(find xacro)/xacro --inorder '$(find arm_description)/urdf/arm.urdf.xacro' prefix:=$(arg prefix)"/>
      </launch>)~");
    writeFile(dir_.path() / "arm_control/config/control.yaml",
              "joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 50}\n");
    writeFile(dir_.path() / "arm_control/launch/bringup.launch", R"~(<launch>
        <arg name="paused" default="false"/>
        <arg name="prefix" default="left_"/>
        <arg name="with_gripper" default="false"/>
        <include file="$(find gazebo_ros)/launch/empty_world.launch">
          <arg name="paused" value="$(arg paused)"/>
          <arg name="use_sim_time" value="true"/>
        </include>
        <group ns="arm">
          <include file="$(find arm_description)/launch/description.launch">
            <arg name="prefix" value="$(arg prefix)"/>
          </include>
          <rosparam file="$(find arm_control)/config/control.yaml" command="load"/>
          <rosparam>hinge_controller: {type: effort_controllers/JointPositionController, joint: left_hinge}</rosparam>
          <rosparam param="hinge_controller/pid">{p: 100.0, i: 0.01, d: 10.0}</rosparam>
          <param name="rate" value="  50  "/>
          <param name="label" value="front arm"/>
          <param name="enabled" value="True"/>
          <param name="code" type="str" value="007"/>
          <node name="spawn" pkg="gazebo_ros" type="spawn_model"
                args="-urdf -param robot_description -model arm -x 0.5 -z 0.1 -Y 1.5 -J left_hinge 0.3"/>
          <node name="spawner" pkg="controller_manager" type="spawner" args="--wait-for initialized joint_state_controller -t 5 hinge_controller"/>
          <node name="gripper_spawner" pkg="controller_manager" type="spawner" args="gripper_controller" if="$(arg with_gripper)"/>
          <node name="later" pkg="controller_manager" type="spawner" args="--stopped hinge_controller_2"/>
          <node name="rsp" pkg="robot_state_publisher" type="robot_state_publisher"/>
        </group>
        <node name="rviz" pkg="rviz" type="rviz" unless="$(arg paused)"/>
      </launch>)~");
    setenv("ROS_PACKAGE_PATH", dir_.path().c_str(), 1);
  }
  void TearDown() override { unsetenv("ROS_PACKAGE_PATH"); }

  std::string errorOf(const std::string& launch_text, const std::map<std::string, std::string>& args = {}) {
    writeFile(dir_.path() / "t.launch", launch_text);
    try {
      loadLaunchFile(dir_.path() / "t.launch", args);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }

  TempDir dir_{"servoloop-roslaunch"};
};

TEST_F(RoslaunchProject, BringUpReadsToOneRobotWithItsControllersAndParameters) {
  const LaunchFile launch = loadLaunchFile(dir_.path() / "arm_control/launch/bringup.launch");
  EXPECT_TRUE(launch.world.ground_plane) << "Gazebo's empty world has a ground plane";
  ASSERT_EQ(launch.robots.size(), 1u);
  const RobotSpec& robot = launch.robots[0];
  EXPECT_EQ(robot.urdf, dir_.path() / "arm_description/urdf/arm.urdf.xacro");
  EXPECT_EQ(robot.xacro_args, (std::map<std::string, std::string>{{"prefix", "left_"}}));
  EXPECT_EQ(robot.model, "arm");
  EXPECT_EQ(robot.robot_namespace, "/arm");  // the spawn_model node's namespace
  ASSERT_TRUE(robot.pose.has_value());
  EXPECT_EQ(*robot.pose, (std::array<double, 6>{0.5, 0.0, 0.1, 0.0, 0.0, 1.5}));
  EXPECT_EQ(robot.controllers, (std::vector<std::string>{"joint_state_controller", "hinge_controller"}));
  EXPECT_EQ(robot.stopped_controllers, std::vector<std::string>{"hinge_controller_2"});

  // Parameters in launch-file order, then the robot's start position.
  ASSERT_EQ(robot.params.size(), 8u);
  EXPECT_EQ(robot.params[0].file, dir_.path() / "arm_control/config/control.yaml");
  EXPECT_EQ(robot.params[0].ns, "/arm");
  EXPECT_EQ(robot.params[1].ns, "/arm");
  EXPECT_CONTAINS(robot.params[1].yaml, "hinge_controller: {type: effort_controllers/JointPositionController");
  EXPECT_EQ(robot.params[2].ns, "/arm/hinge_controller");
  EXPECT_EQ(robot.params[2].yaml, "pid:\n  {p: 100.0, i: 0.01, d: 10.0}");
  EXPECT_EQ(robot.params[3].yaml, "rate: 50");  // value="  50  ": roslaunch strips it, an int
  EXPECT_EQ(robot.params[4].yaml, "label: \"front arm\"");
  EXPECT_EQ(robot.params[5].yaml, "enabled: true");
  EXPECT_EQ(robot.params[6].yaml, "code: \"007\"");
  EXPECT_EQ(robot.params[7].ns, "/arm/sim");
  EXPECT_EQ(robot.params[7].yaml, "initial_positions:\n  left_hinge: 0.3");
  EXPECT_CONTAINS(robot.params[3].source_name, "bringup.launch:16");
}

TEST_F(RoslaunchProject, CommandLineArgumentsOverrideDefaults) {
  const LaunchFile launch =
      loadLaunchFile(dir_.path() / "arm_control/launch/bringup.launch", {{"prefix", "right_"}, {"with_gripper", "true"}});
  ASSERT_EQ(launch.robots.size(), 1u);
  EXPECT_EQ(launch.robots[0].xacro_args.at("prefix"), "right_");
  EXPECT_EQ(launch.robots[0].controllers,
            (std::vector<std::string>{"joint_state_controller", "hinge_controller", "gripper_controller"}));
}

TEST_F(RoslaunchProject, EvalTakesArgumentsAsText) {
  writeFile(dir_.path() / "r.urdf", robotUrdf("r"));
  const std::string launch = R"~(<launch>
      <arg name="mode" default="sim"/>
      <arg name="count" default="2"/>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -file r.urdf -model r"/>
      <node name="a" pkg="controller_manager" type="spawner" args="a" if="$(eval arg('mode') == 'sim' and count == '2')"/>
      <node name="b" pkg="controller_manager" type="spawner" args="b" if="$(eval mode != 'sim')"/>
      <node name="c" pkg="controller_manager" type="spawner" args="$(eval 'c' * int(count))"/>
    </launch>)~";
  EXPECT_EQ(errorOf(launch), "");
  EXPECT_EQ(loadLaunchFile(dir_.path() / "t.launch").robots[0].controllers, (std::vector<std::string>{"a", "cc"}));
  EXPECT_EQ(loadLaunchFile(dir_.path() / "t.launch", {{"mode", "real"}}).robots[0].controllers,
            (std::vector<std::string>{"b", "cc"}));
  EXPECT_CONTAINS(errorOf(R"~(<launch><group if="$(eval undefined_arg == 1)"/></launch>)~"),
                  "t.launch:1: <group>: $(eval undefined_arg == 1): name 'undefined_arg' is not defined");
}

// franka_gazebo loads its controller YAML with subst_value="true": the
// file's $(arg arm_id)_joint1 names are substituted before it is read.
TEST_F(RoslaunchProject, RosparamFileWithSubstValueSubstitutesTheFilesText) {
  writeFile(dir_.path() / "r.urdf", robotUrdf("r"));
  writeFile(dir_.path() / "gains.yaml", "c:\n  joint: $(arg arm)_hinge\n  gains:\n    $(arg arm)_hinge: {p: 5}\n");
  EXPECT_EQ(errorOf(R"~(<launch>
      <arg name="arm" default="left"/>
      <rosparam file="gains.yaml" subst_value="true"/>
      <rosparam file="gains.yaml"/>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -file r.urdf -model r"/>
    </launch>)~"),
            "");
  const LaunchFile launch = loadLaunchFile(dir_.path() / "t.launch");
  ASSERT_EQ(launch.robots.size(), 1u);
  const std::vector<ParameterFile>& params = launch.robots[0].params;
  ASSERT_EQ(params.size(), 2u);
  EXPECT_TRUE(params[0].file.empty());
  EXPECT_EQ(params[0].yaml, "c:\n  joint: left_hinge\n  gains:\n    left_hinge: {p: 5}\n");
  EXPECT_EQ(params[0].source_name, (dir_.path() / "gains.yaml").string());
  EXPECT_EQ(params[1].file, dir_.path() / "gains.yaml");  // without subst_value, loaded as it is
  EXPECT_CONTAINS(errorOf(R"~(<launch><rosparam file="nope.yaml" subst_value="true"/></launch>)~"),
                  "t.launch:1: <rosparam>: ");
  EXPECT_CONTAINS(errorOf(R"~(<launch><rosparam file="nope.yaml" subst_value="true"/></launch>)~"), "nope.yaml");
}

TEST_F(RoslaunchProject, RobotNamespaceFromTheUrdfPlacesTheSpawnerAsGazeboDoes) {
  writeFile(dir_.path() / "ns_robot.urdf",
            robotUrdf("ns_robot", R"~(<gazebo><plugin name="c" filename="libgazebo_ros_control.so">
              <robotNamespace>/custom</robotNamespace></plugin></gazebo>)~"));
  EXPECT_EQ(errorOf(R"~(<launch>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -file ns_robot.urdf -model r"/>
      <node name="c" pkg="controller_manager" type="spawner" ns="custom" args="a"/>
      <node name="d" pkg="controller_manager" type="controller_manager" ns="/custom" args="load b"/>
    </launch>)~"),
            "");
  const LaunchFile launch = loadLaunchFile(dir_.path() / "t.launch");
  EXPECT_EQ(launch.robots[0].controllers, std::vector<std::string>{"a"});
  EXPECT_EQ(launch.robots[0].stopped_controllers, std::vector<std::string>{"b"});
}

TEST_F(RoslaunchProject, MistakesNameTheFileLineAndFix) {
  writeFile(dir_.path() / "r.urdf", robotUrdf("r"));
  EXPECT_CONTAINS(errorOf("<launch>\n<param name=\"x\" value=\"$(arg nope)\"/></launch>"),
                  "t.launch:2: <param>: $(arg nope): no <arg name=\"nope\"> is declared");
  EXPECT_CONTAINS(errorOf(R"~(<launch><arg name="needed"/></launch>)~"),
                  "arg 'needed' has no default and was not passed; pass needed:=value");
  EXPECT_CONTAINS(errorOf(R"~(<launch><arg name="a" default="1"/></launch>)~", {{"b", "2"}}),
                  "argument(s) b are not declared by this launch file (its <arg>s: a)");
  EXPECT_CONTAINS(errorOf("<launch>\n<arg name=\"a\" default=\"1\"/>\n<arg name=\"a\" default=\"2\"/></launch>"),
                  "t.launch:3: <arg>: arg 'a' has already been declared (at line 2), as roslaunch says too");
  // The <arg>s of an <include> are declared in the included file: once each.
  EXPECT_CONTAINS(errorOf("<launch>\n<include file=\"x.launch\">\n<arg name=\"a\" value=\"1\"/>\n"
                          "<arg name=\"a\" value=\"2\"/>\n</include></launch>"),
                  "t.launch:4: <arg>: arg 'a' has already been declared in this <include> (at line 3)");
  // No document type, so no entities (an XML bomb's stuff), wherever they are.
  EXPECT_CONTAINS(errorOf("<?xml version=\"1.0\"?>\n<!DOCTYPE launch [<!ENTITY a \"1\">]>\n"
                          "<launch><arg name=\"x\" default=\"&a;\"/></launch>"),
                  "t.launch:2: <!DOCTYPE...> is refused: a roslaunch file has no document type (DTD) and no "
                  "<!ENTITY>");
  EXPECT_CONTAINS(errorOf("<launch>\n<group>\n<!ENTITY b \"2\">\n</group></launch>"),
                  "t.launch:3: <!ENTITY...> is refused");
  EXPECT_CONTAINS(errorOf(R"~(<launch><group if="maybe"/></launch>)~"),
                  "if=\"maybe\" gives 'maybe', which is neither true/1 nor false/0");
  EXPECT_CONTAINS(errorOf(R"~(<launch><nodes/></launch>)~"), "<nodes> is not a roslaunch element");
  EXPECT_CONTAINS(errorOf(R"~(<launch>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model r"/></launch>)~"),
                  "spawn_model -param /robot_description: no <param name=\"/robot_description\"");
  EXPECT_CONTAINS(errorOf(R"~(<launch><param name="robot_description" command="python3 make_urdf.py"/>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description -model r"/></launch>)~"),
                  "is not `xacro FILE [name:=value ...]` or `cat FILE`");
  EXPECT_CONTAINS(errorOf(R"~(<launch>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -file r.urdf -model r"/>
      <node name="c" pkg="controller_manager" type="spawner" ns="elsewhere" args="a"/></launch>)~"),
                  "t.launch:3: the controller spawner in namespace /elsewhere has no robot there (robots spawned: /)");
  EXPECT_CONTAINS(errorOf(R"~(<launch>
      <node name="s" pkg="gazebo_ros" type="spawn_model" args="-urdf -file r.urdf -model r -x far"/></launch>)~"),
                  "spawn_model -x far: not a number");
  EXPECT_CONTAINS(errorOf(R"~(<launch><include file="missing.launch"/></launch>)~"), "missing.launch' cannot be read");
  EXPECT_CONTAINS(errorOf("<launch><param name="), "t.launch:1: not well-formed roslaunch XML");
  EXPECT_CONTAINS(errorOf(R"~(<launch><include file="t.launch"/></launch>)~"), "includes nest more than 50 deep");
}

}  // namespace
}  // namespace servoloop::node
