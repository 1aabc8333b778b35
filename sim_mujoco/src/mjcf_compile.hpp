#pragma once
// MJCF text compiled by MuJoCo from memory (an in-memory file system).
#include <string>

struct mjModel_;

namespace servoloop::sim_mujoco {

// Non-real-time. The compiled model (the caller owns it: mj_deleteModel).
// Throws servoloop::ConfigError naming `source_name` with MuJoCo's message
// when it refuses the model.
mjModel_* compileMjcf(const std::string& mjcf, const std::string& source_name);

}  // namespace servoloop::sim_mujoco
