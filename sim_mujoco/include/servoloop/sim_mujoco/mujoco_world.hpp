#pragma once
// The "mujoco/world" plugin: one MuJoCo model and data that every robot of a
// node on the mujoco backend is built into, so that they touch each other.
//
// MuJoCo compiles a whole model at once, so a robot joining or leaving
// recompiles the world from every robot's share (MjcfParts, names prefixed
// per robot) and carries each remaining joint's state (position, velocity,
// warm start) and the time over by name; the node does this between two
// cycles. Each robot's MujocoPhysics then binds to the new model and data.
// The world's step() is one mj_step after every robot handed over its
// efforts (each robot's step() solves its motors on the shared state).
#include <memory>
#include <string>
#include <vector>

#include "servoloop/hardware_interface/simulated_world.hpp"
#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"

struct mjModel_;
struct mjData_;

namespace servoloop::sim_mujoco {

class MujocoPhysics;

class MujocoWorld final : public hardware_interface::SimulatedWorld {
 public:
  MujocoWorld();
  ~MujocoWorld() override;
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  void init(const hardware_interface::SimulatedWorldSettings& settings) override;
  const hardware_interface::SimulatedWorldSettings& settings() const noexcept override { return settings_; }
  bool robotsTouch() const noexcept override { return true; }
  // Real-time: one mj_step of the whole world.
  ReturnType step() noexcept override;
  // Warm starts, applied forces and time forgotten; every body stays where it is.
  void restart() override;

  // Non-real-time, no step running: a name prefix no robot of this world had.
  std::string newPrefix();
  // (add's `robot_name` is the robot's model name, for messages.)
  // Non-real-time, no step running: `robot`'s share built into the world
  // (recompiled, the others' state carried over), then every robot bound to
  // the new model. Throws servoloop::ConfigError naming `source_name` when
  // MuJoCo refuses the model; the world is then as it was.
  void add(MujocoPhysics& robot, MjcfParts parts, const std::string& source_name, const std::string& robot_name);
  // Non-real-time, no step running: `robot` taken out, the others carried over.
  void remove(MujocoPhysics& robot) noexcept;

  // The name of the robot whose names start with `prefix` ("" for none).
  std::string robotName(const std::string& prefix) const;
  // The MJCF the world compiled last ("" with no robot).
  const std::string& mjcf() const noexcept { return mjcf_; }

 private:
  struct Member {
    MujocoPhysics* robot;
    MjcfParts parts;
    std::string prefix;
    std::string name;
  };
  struct ModelDeleter {
    void operator()(mjModel_* model) const noexcept;
  };
  struct DataDeleter {
    void operator()(mjData_* data) const noexcept;
  };
  void rebuild(std::vector<Member> members, const std::string& source_name);

  hardware_interface::SimulatedWorldSettings settings_;
  bool initialised_ = false;
  std::vector<Member> members_;
  std::unique_ptr<mjModel_, ModelDeleter> model_;
  std::unique_ptr<mjData_, DataDeleter> data_;
  std::string mjcf_;
  unsigned next_prefix_ = 0;
};

}  // namespace servoloop::sim_mujoco
