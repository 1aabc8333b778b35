#include "servoloop/controllers/diff_drive_controller/wheel_geometry.hpp"

#include <cmath>

#include "servoloop/core/errors.hpp"

namespace servoloop::controllers::diff_drive_controller {
namespace {

urdf::JointConstSharedPtr requireJoint(const urdf::ModelInterface& model, const std::string& name,
                                       const std::string& controller_name, const char* parameter) {
  urdf::JointConstSharedPtr joint = model.getJoint(name);
  if (!joint) {
    throw ConfigError("controller '" + controller_name + "': the robot description has no joint '" + name +
                      "' (named by " + parameter + ")");
  }
  return joint;
}

// The joint's origin in the root link's frame.
urdf::Vector3 originInRoot(const urdf::ModelInterface& model, const urdf::JointConstSharedPtr& joint) {
  urdf::Vector3 position = joint->parent_to_joint_origin_transform.position;
  std::string link = joint->parent_link_name;
  for (int depth = 0; depth < 1000; ++depth) {
    urdf::LinkConstSharedPtr parent = model.getLink(link);
    if (!parent || !parent->parent_joint) break;
    const urdf::Pose& up = parent->parent_joint->parent_to_joint_origin_transform;
    position = up.rotation * position + up.position;
    link = parent->parent_joint->parent_link_name;
  }
  return position;
}

}  // namespace

double wheelSeparationFromUrdf(const urdf::ModelInterface& model, const std::string& left_joint,
                               const std::string& right_joint, const std::string& controller_name) {
  const urdf::Vector3 left = originInRoot(model, requireJoint(model, left_joint, controller_name, "left_wheel"));
  const urdf::Vector3 right = originInRoot(model, requireJoint(model, right_joint, controller_name, "right_wheel"));
  const double separation =
      std::sqrt((left.x - right.x) * (left.x - right.x) + (left.y - right.y) * (left.y - right.y) +
                (left.z - right.z) * (left.z - right.z));
  if (!(separation > 0.0)) {
    throw ConfigError("controller '" + controller_name + "': wheel joints '" + left_joint + "' and '" + right_joint +
                      "' are at the same place in the URDF; give wheel_separation");
  }
  return separation;
}

double wheelRadiusFromUrdf(const urdf::ModelInterface& model, const std::string& wheel_joint,
                           const std::string& controller_name) {
  const urdf::JointConstSharedPtr joint = requireJoint(model, wheel_joint, controller_name, "left_wheel/right_wheel");
  const urdf::LinkConstSharedPtr link = model.getLink(joint->child_link_name);
  const std::string fix = "; give wheel_radius in the controller's parameters";
  if (!link || !link->collision || !link->collision->geometry) {
    throw ConfigError("controller '" + controller_name + "': wheel link '" + joint->child_link_name +
                      "' has no collision geometry to take the wheel radius from" + fix);
  }
  const urdf::GeometrySharedPtr& geometry = link->collision->geometry;
  if (geometry->type == urdf::Geometry::CYLINDER) {
    return std::static_pointer_cast<const urdf::Cylinder>(geometry)->radius;
  }
  if (geometry->type == urdf::Geometry::SPHERE) {
    return std::static_pointer_cast<const urdf::Sphere>(geometry)->radius;
  }
  throw ConfigError("controller '" + controller_name + "': wheel link '" + joint->child_link_name +
                    "' collides as neither a cylinder nor a sphere, so its radius is unknown" + fix);
}

}  // namespace servoloop::controllers::diff_drive_controller
