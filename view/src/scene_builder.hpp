#pragma once
// The scene the page draws, from each model's URDF: links with their visual
// and collision geometry (boxes, cylinders, spheres, meshes with their
// served URLs) and colours, joints with origins and axes, in the message
// form docs/view.md gives. The page computes each link's pose from the
// model's base pose and joint positions (URDF kinematics), so that a frame
// carries only those.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "static_files.hpp"

namespace servoloop::view {

struct SceneModel {
  std::string name;  // the model (URDF robot) name
  std::string ns;    // its namespace
  std::string urdf;  // the robot description
  std::string path;  // the URDF's file, for meshes given relative to it
  std::vector<std::string> joint_names;  // the order of the frame's positions
};

// The page's scene message for `models` ({"type": "scene", ...}); meshes
// are registered with `files`. A model whose URDF cannot be read is left
// out and named in `warnings`; so is a mesh file that does not exist (the
// page then draws that link's collision shapes).
nlohmann::json buildScene(const std::vector<SceneModel>& models, bool ground_plane, StaticFiles& files,
                          std::vector<std::string>& warnings);

// The colour of one of Gazebo's named materials (Gazebo/Red, ...) as r, g, b,
// a; empty for a name it does not know.
std::vector<double> gazeboMaterialColor(const std::string& name);

}  // namespace servoloop::view
