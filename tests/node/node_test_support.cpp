#include "node_test_support.hpp"

#include <stdlib.h>

#include <fstream>
#include <sstream>

#include "servoloop/controller_manager/plugin_loader.hpp"

namespace servoloop::node_test {

fs::path oneDofDir() { return fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof"; }

controller_manager::node::LaunchFile seedLaunch(const std::string& backend) {
  auto launch = controller_manager::node::loadLaunchFile(oneDofDir() / "one_dof_w_jnt_ctl.launch.yaml");
  launch.world.backend = backend;
  return launch;
}

TempDir::TempDir(const std::string& prefix) {
  std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code error;
  fs::remove_all(path_, error);
}

bool backendAvailable(const std::string& backend) {
  controller_manager::PluginLoader loader;
  for (const auto& type : loader.listTypes("robot_hw")) {
    if (type.type == backend) return true;
  }
  return false;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace servoloop::node_test
