#pragma once
#include <string>

namespace servoloop::hardware_interface {

// Read-only view of one actuator's state, in actuator space (motor side of a
// transmission).
class ActuatorStateHandle {
 public:
  ActuatorStateHandle() = default;
  // Throws servoloop::Error if any pointer is null.
  ActuatorStateHandle(std::string name, const double* position, const double* velocity,
                      const double* effort);

  const std::string& getName() const { return name_; }
  double getPosition() const { return *position_; }
  double getVelocity() const { return *velocity_; }
  double getEffort() const { return *effort_; }
  const double* getPositionPtr() const { return position_; }
  const double* getVelocityPtr() const { return velocity_; }
  const double* getEffortPtr() const { return effort_; }

 private:
  std::string name_;
  const double* position_ = nullptr;
  const double* velocity_ = nullptr;
  const double* effort_ = nullptr;
};

}  // namespace servoloop::hardware_interface
