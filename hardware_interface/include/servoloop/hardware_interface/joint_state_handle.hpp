#pragma once
#include <string>

namespace servoloop::hardware_interface {

// Read-only view of one joint's state, in joint space (rad or m, rad/s or m/s,
// N·m or N). Points into storage owned by the RobotHW; copying is cheap and
// reading is real-time safe.
class JointStateHandle {
 public:
  JointStateHandle() = default;
  // Throws servoloop::Error if any pointer is null.
  JointStateHandle(std::string name, const double* position, const double* velocity,
                   const double* effort);

  const std::string& getName() const { return name_; }
  double getPosition() const { return *position_; }
  double getVelocity() const { return *velocity_; }
  double getEffort() const { return *effort_; }
  const double* getPositionPtr() const { return position_; }
  const double* getVelocityPtr() const { return velocity_; }
  const double* getEffortPtr() const { return effort_; }
  bool valid() const { return position_ != nullptr; }

 private:
  std::string name_;
  const double* position_ = nullptr;
  const double* velocity_ = nullptr;
  const double* effort_ = nullptr;
};

}  // namespace servoloop::hardware_interface
