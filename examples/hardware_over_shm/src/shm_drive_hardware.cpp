// example/ShmDriveHardware: a servoloop robot_hw plugin for the drive process
// of servoloop_example_drive, over shared memory (drive_link.hpp).
//
// Parameters (the launch file's `hardware:` keys):
//   drive: the drive's shared-memory name (default servoloop_example_drive)
//   joints: [..] the URDF joints, in the drive's motor order
//   counts_per_rev: the encoders' resolution (default 4096)
//   heartbeat_timeout: s without a new drive cycle before read() fails (default 0.05)
//
// Interfaces: JointStateInterface and EffortJointInterface (torque commands).
// read() fails (ReturnType::error) while the drive's heartbeat is older than
// the timeout — the drive was killed or hangs — so the node goes into a
// protective stop; once the drive runs again, `servoloop control recover`
// takes the robot back.
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/hardware_interface/robot_hw.hpp"
#include "servoloop/plugin/plugin_register.hpp"
#include "shm_drive/drive_link.hpp"

namespace shm_drive {

namespace hi = servoloop::hardware_interface;

class ShmDriveHardware : public hi::RobotHW {
 public:
  void init(const hi::HardwareInfo& info) override {
    const YAML::Node params = info.parameters["hardware"];
    const std::string where = "hardware (" + info.robot_namespace + "/hardware)";
    if (!params || !params["joints"] || !params["joints"].IsSequence() || params["joints"].size() == 0) {
      throw servoloop::ConfigError(where + ": example/ShmDriveHardware needs joints: [..], the URDF joints in the "
                                           "drive's motor order");
    }
    const auto names = params["joints"].as<std::vector<std::string>>();
    const std::string drive = params["drive"] ? params["drive"].as<std::string>() : "servoloop_example_drive";
    const double counts_per_rev = params["counts_per_rev"] ? params["counts_per_rev"].as<double>() : 4096.0;
    const double timeout_s = params["heartbeat_timeout"] ? params["heartbeat_timeout"].as<double>() : 0.05;
    if (!(counts_per_rev > 0.0) || !(timeout_s > 0.0)) {
      throw servoloop::ConfigError(where + ": counts_per_rev and heartbeat_timeout must be positive");
    }
    try {
      link_.emplace(DriveLink::attach(drive));
    } catch (const std::runtime_error& e) {
      throw servoloop::ConfigError(where + ": " + e.what());
    }
    const std::uint32_t motors = link_->image().joint_count.load(std::memory_order_relaxed);
    if (motors != names.size()) {
      throw servoloop::ConfigError(where + ": drive '" + drive + "' has " + std::to_string(motors) +
                                   " motor(s) but joints lists " + std::to_string(names.size()) +
                                   "; start it with --joints " + std::to_string(names.size()));
    }
    rad_per_count_ = 2.0 * M_PI / counts_per_rev;
    timeout_ns_ = static_cast<std::int64_t>(timeout_s * 1e9);
    joints_.resize(names.size());
    for (std::size_t j = 0; j < names.size(); ++j) {
      hi::JointStateHandle state(names[j], &joints_[j].position, &joints_[j].velocity, &joints_[j].effort);
      state_interface_.registerHandle(state);
      effort_interface_.registerHandle(hi::JointHandle(state, &joints_[j].command));
    }
    registerInterface(&state_interface_);
    registerInterface(&effort_interface_);
  }

  servoloop::ReturnType read(servoloop::Time /*time*/, servoloop::Duration /*period*/) override {
    const DriveImage& image = link_->image();
    const std::int64_t heartbeat_ns = image.heartbeat_ns.load(std::memory_order_acquire);
    if (DriveLink::nowNs() - heartbeat_ns > timeout_ns_) return servoloop::ReturnType::error;  // drive not running
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      joints_[j].position = static_cast<double>(image.encoder_counts[j].load(std::memory_order_relaxed)) * rad_per_count_;
      joints_[j].velocity = image.velocity_counts_per_s[j].load(std::memory_order_relaxed) * rad_per_count_;
    }
    return servoloop::ReturnType::ok;
  }

  servoloop::ReturnType write(servoloop::Time /*time*/, servoloop::Duration /*period*/) override {
    DriveImage& image = link_->image();
    for (std::size_t j = 0; j < joints_.size(); ++j) {
      image.torque_command[j].store(joints_[j].command, std::memory_order_relaxed);
      joints_[j].effort = joints_[j].command;  // what the motor is asked for
    }
    return servoloop::ReturnType::ok;
  }

 private:
  struct Joint {
    double position = 0.0, velocity = 0.0, effort = 0.0, command = 0.0;
  };
  std::optional<DriveLink> link_;
  std::vector<Joint> joints_;  // sized in init, before handles point into it
  hi::JointStateInterface state_interface_;
  hi::EffortJointInterface effort_interface_;
  double rad_per_count_ = 0.0;
  std::int64_t timeout_ns_ = 0;
};

}  // namespace shm_drive

SERVOLOOP_REGISTER_PLUGIN(shm_drive::ShmDriveHardware, servoloop::hardware_interface::RobotHW,
                          "example/ShmDriveHardware")
