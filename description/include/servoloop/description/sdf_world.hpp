#pragma once
// SDFormat world files (Gazebo's .world / .sdf), read with Debian's
// libsdformat (SDFormat 12): the world's physics settings and its models,
// each model turned into a URDF that the simulators load like any robot's.
//
// What is read: <physics><max_step_size>, <gravity>,
// top-level <model>s (also from <include>) with their links (inertial,
// collisions and visuals — box, cylinder, sphere, mesh — with poses and
// material colours, <surface><friction><ode><mu>/<mu2>), joints (revolute,
// continuous, prismatic, fixed; axis, limits, damping and friction),
// <static> and the model's pose. model://ground_plane and model://sun are
// built in: a static model whose only collision is an upward plane through
// the origin is the world's ground plane. Other model:// URIs are looked up
// in GAZEBO_MODEL_PATH and SDF_PATH, as Gazebo does.
//
// What servoloop does not simulate — lights, sensors, plugins, actors, the
// GUI, nested models, geometry other than the above — is one warning each.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace servoloop {

// One model of the world, as a robot description.
struct SdfWorldModel {
  std::string name;               // the SDF model's name
  std::string urdf;               // its URDF text (absolute mesh paths)
  bool fixed_base = false;        // <static>, or joined to the world by a fixed joint
  std::array<double, 6> pose{};   // its root link in the world: x y z (m) roll pitch yaw (rad)
};

struct SdfWorld {
  std::string name;
  std::optional<double> time_step_s;        // <physics><max_step_size>
  std::array<double, 3> gravity{0.0, 0.0, -9.81};
  bool ground_plane = false;                // model://ground_plane, or a model like it
  std::vector<SdfWorldModel> models;
  // What was left out, one line each (the caller logs them).
  std::vector<std::string> warnings;
};

// True for a path servoloop reads as an SDFormat world (.world or .sdf).
bool isSdfWorldPath(const std::filesystem::path& path);

// Reads `file`. Throws servoloop::ConfigError with libsdformat's messages
// (file and line) for a file that does not parse or validate, and naming the
// model, link or joint for what cannot be simulated (a joint type without a
// URDF counterpart, links not joined into one tree).
SdfWorld readSdfWorld(const std::filesystem::path& file);

}  // namespace servoloop
