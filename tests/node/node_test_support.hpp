#pragma once
// Shared helpers of the node tests: the seed's files, temporary folders and a
// private IPC run directory.
#include <filesystem>
#include <string>

#include "servoloop/controller_manager/node/launch_file.hpp"

namespace servoloop::node_test {

namespace fs = std::filesystem;

// robots/one_dof in the source tree.
fs::path oneDofDir();
// The seed launch file (robots/one_dof/one_dof_w_jnt_ctl.launch.yaml) with
// the backend replaced.
controller_manager::node::LaunchFile seedLaunch(const std::string& backend);

// A fresh, private (0700) folder under the system temp folder, removed when
// the object dies.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// True if the plugin folder has a robot_hw backend of that type.
bool backendAvailable(const std::string& backend);

std::string readFile(const fs::path& path);

}  // namespace servoloop::node_test
