#pragma once
// The physics backends this build has, for tests parameterised over them
// (the CMake function servoloop_add_backend_cli_test defines the macros).
#include <string>
#include <vector>

namespace servoloop::testing {

inline std::vector<std::string> physicsBackends() {
  std::vector<std::string> names;
#ifdef SERVOLOOP_HAVE_BULLET
  names.push_back("bullet");
#endif
#ifdef SERVOLOOP_HAVE_MUJOCO
  names.push_back("mujoco");
#endif
  return names;
}

}  // namespace servoloop::testing
