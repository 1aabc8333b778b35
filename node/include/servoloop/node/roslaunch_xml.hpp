#pragma once
// ROS launch files (roslaunch XML, `.launch`) read into a servoloop
// LaunchFile: the parts that describe a simulated robot, as a ROS user runs
// them under Gazebo with gazebo_ros_control.
//
//   <arg>, `name:=value` arguments, $(arg), $(find), $(env), $(optenv),
//   $(dirname), $(anon), $(eval) (a whole attribute); `if`/`unless` on every
//   element; <group ns>;
//   <include file ns pass_all_args> with <arg> children;
//   <param name value|textfile|command type> (command: xacro FILE name:=value);
//   <rosparam file|text command="load" ns param subst_value>;
//   <node pkg="gazebo_ros" type="spawn_model" args="-urdf -param P | -file F
//     -model M -x -y -z -R -P -Y -J joint value -robot_namespace NS">;
//   <node pkg="controller_manager" type="spawner" args="c1 c2 [--stopped]" ns>
//     (and type="controller_manager" args="spawn|load c1 ...");
//   an <include> of gazebo_ros's world launch files stands for Gazebo's empty
//   world: a ground plane.
//
// Other nodes (robot_state_publisher, rviz, the user's own) are not run; they
// are listed once in one warning. Errors are servoloop::ConfigError naming
// the file, the line, the element and the fix. Non-real-time.
#include <filesystem>
#include <map>
#include <string>

#include "servoloop/node/launch_file.hpp"

namespace servoloop::node {

// True for a roslaunch XML file (".launch", or ".xml" such as "x.launch.xml").
bool isRoslaunchPath(const std::filesystem::path& path);

// Reads the roslaunch file at `path` with the command line's `name:=value`
// arguments.
LaunchFile loadRoslaunchFile(const std::filesystem::path& path, const std::map<std::string, std::string>& args);

}  // namespace servoloop::node
