#include "servoloop/sim_common/wheel_contact.hpp"

#include <cmath>

namespace servoloop::sim_common {

bool isWheelCylinder(const urdf::Joint* parent_joint, const Eigen::Matrix3d& cylinder_in_link, double radius,
                     double length) {
  if (parent_joint == nullptr) return false;
  if (parent_joint->type != urdf::Joint::REVOLUTE && parent_joint->type != urdf::Joint::CONTINUOUS) return false;
  if (!(length > 0.0) || !(length <= radius)) return false;
  const Eigen::Vector3d axis(parent_joint->axis.x, parent_joint->axis.y, parent_joint->axis.z);
  if (!(axis.norm() > 0.0)) return false;
  const Eigen::Vector3d cylinder_axis = cylinder_in_link.col(2);
  constexpr double kParallel = 1e-6;  // 1 - |cos| of the angle between the axes
  return 1.0 - std::abs(cylinder_axis.dot(axis.normalized())) < kParallel;
}

}  // namespace servoloop::sim_common
