#pragma once
// The ROS tools (rostopic, rosservice, rosbag, rqt) are Python programs that
// import a message's package to read it. Debian lacks control_msgs,
// controller_manager_msgs and gazebo_msgs; servoloop generates them (genpy)
// into share/servoloop/ros1/python beside its programs, in the build tree and
// where `cmake --install` puts them. This makes them visible to every Python
// of the user without a manual step: a file Python reads at start, a `.pth`
// in the user's site-packages (site.getusersitepackages(), e.g.
// ~/.local/lib/python3.11/site-packages/servoloop_ros1_messages.pth) naming
// that folder, written when it is missing or names another one.
#include <filesystem>
#include <string>

namespace servoloop::ros1 {

struct PythonMessagesRegistration {
  bool registered = false;          // the .pth names `folder` now
  bool written = false;             // ... because it was written just now
  std::filesystem::path pth;        // the file
  std::filesystem::path folder;     // the generated packages
  std::string why_not;              // what stopped it, when not registered
};

// `program`: this executable's path (its folder's ../share/servoloop/ros1/python
// holds the packages). `python`: the Python whose user site-packages to use
// (Debian's /usr/bin/python3). Never throws.
PythonMessagesRegistration registerPythonMessages(const std::filesystem::path& program,
                                                  const std::filesystem::path& python = "/usr/bin/python3");

}  // namespace servoloop::ros1
