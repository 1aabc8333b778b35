#include "mjcf_compile.hpp"

#include <cstring>
#include <memory>

#include <mujoco/mujoco.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_mujoco {
namespace {
constexpr const char* kModelFileName = "servoloop_model.xml";
}  // namespace

// Compiles MJCF text from memory: one file in a virtual file system (which is
// ~2 MB, hence on the heap).
mjModel* compileMjcf(const std::string& mjcf, const std::string& source_name) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kModelFileName, static_cast<int>(mjcf.size())) != 0) {
    throw Error(source_name + ": could not create MuJoCo's in-memory model file");
  }
  const int file = mj_findFileVFS(vfs.get(), kModelFileName);
  std::memcpy(vfs->filedata[file], mjcf.data(), mjcf.size());
  char error[1024] = "";
  mjModel* model = mj_loadXML(kModelFileName, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (model == nullptr) {
    const std::string text = error;
    // mjcfFromUrdf refuses a tree deeper than tinyxml2's limit up front; a
    // MuJoCo built on another tinyxml2 may stop sooner, with words that say
    // nothing of the robot.
    if (text.find("XML_ELEMENT_DEPTH_EXCEEDED") != std::string::npos) {
      throw ConfigError(source_name + ": a kinematic chain of the robot is too deep for MuJoCo: its model nests one "
                                      "body inside another for each joint of a chain, and MuJoCo's XML reader "
                                      "refused that many levels; use the bullet or mock backend, or a shallower tree");
    }
    // A hint only where MuJoCo's own words point at the inertia.
    const bool inertia = text.find("inertia") != std::string::npos || text.find("mass") != std::string::npos;
    throw ConfigError(source_name + ": MuJoCo refused the model generated from the URDF: " + text +
                      (inertia ? " (check the link's <inertial>: MuJoCo needs principal moments with A + B >= C)" : ""));
  }
  return model;
}


}  // namespace servoloop::sim_mujoco
