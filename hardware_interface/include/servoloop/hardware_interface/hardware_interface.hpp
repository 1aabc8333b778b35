#pragma once
#include <set>
#include <string>
#include <vector>

namespace servoloop::hardware_interface {

// Base of every interface a RobotHW offers (JointStateInterface,
// EffortJointInterface, ...). Records which resources controllers claimed
// through it while they were being initialised; not used on the real-time path.
class HardwareInterface {
 public:
  virtual ~HardwareInterface();

  // The interface's name as ros_control spells it, e.g. "EffortJointInterface".
  virtual const char* name() const = 0;
  // Names of every handle registered with this interface.
  virtual std::vector<std::string> getNames() const = 0;

  void claim(const std::string& resource) { claims_.insert(resource); }
  const std::set<std::string>& getClaims() const { return claims_; }
  void clearClaims() { claims_.clear(); }

 private:
  std::set<std::string> claims_;
};

}  // namespace servoloop::hardware_interface
