#pragma once
// Shared helpers of the node tests: the seed's files, temporary folders and a
// private IPC run directory.
#include <filesystem>
#include <string>

#include "servoloop/node/launch_file.hpp"
#include "temp_dir.hpp"

namespace servoloop::node_test {

namespace fs = std::filesystem;

// robots/one_dof in the source tree.
fs::path oneDofDir();
// The seed launch file (robots/one_dof/one_dof_w_jnt_ctl.launch.yaml) with
// the backend replaced.
servoloop::node::LaunchFile seedLaunch(const std::string& backend);

// A fresh, private folder under the system temp folder, removed when it dies.
using TempDir = servoloop::testing::TempDir;

// True if the plugin folder has a robot_hw backend of that type.
bool backendAvailable(const std::string& backend);

using servoloop::testing::readFile;

}  // namespace servoloop::node_test
