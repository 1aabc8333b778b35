#include "node_test_support.hpp"

#include <stdlib.h>

#include <fstream>
#include <sstream>

#include "servoloop/plugin/plugin_loader.hpp"

namespace servoloop::node_test {

fs::path oneDofDir() { return fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof"; }

servoloop::node::LaunchFile seedLaunch(const std::string& backend) {
  auto launch = servoloop::node::loadLaunchFile(oneDofDir() / "one_dof_w_jnt_ctl.launch.yaml");
  launch.world.backend = backend;
  return launch;
}

bool backendAvailable(const std::string& backend) {
  servoloop::plugin::PluginLoader loader;
  for (const auto& type : loader.listTypes("robot_hw")) {
    if (type.type == backend) return true;
  }
  return false;
}

}  // namespace servoloop::node_test
