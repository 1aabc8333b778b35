#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/sim_common/collision_mesh.hpp"
#include "servoloop/sim_common/contact_friction.hpp"
#include "servoloop/sim_common/wheel_contact.hpp"

namespace servoloop::sim_mujoco {
namespace {

// Soft-constraint reference of joint stops and joint friction: MuJoCo's
// stiffest safe time constant is 2 steps (it clamps smaller values), with
// critical damping. The impedance 0.95..0.99 leaves a stop pushed by the
// full effort a few microradians deep (see the limit test).
constexpr double kStopTimeConstantInSteps = 2.0;
constexpr const char* kStopImpedance = "0.95 0.99 0.001";
// Contact and constraint-row capacity per body; MuJoCo 2.2 drops contacts
// beyond nconmax (with a warning), so leave room for every body on the ground.
constexpr int kContactsPerBody = 16;
constexpr int kMinContacts = 100;
constexpr int kConstraintRowsPerContact = 6;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

std::string vec3(double x, double y, double z) { return number(x) + " " + number(y) + " " + number(z); }

std::string xmlEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// pos="x y z" quat="w x y z" of a URDF pose.
std::string poseAttributes(const urdf::Pose& pose) {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;
  pose.rotation.getQuaternion(x, y, z, w);
  return "pos=\"" + vec3(pose.position.x, pose.position.y, pose.position.z) + "\" quat=\"" + number(w) + " " +
         vec3(x, y, z) + "\"";
}

// The static body that carries a "world" root link to its spawn pose.
constexpr const char* kSpawnFrameBody = "servoloop_spawn_frame";

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

class MjcfWriter {
 public:
  MjcfWriter(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
             const std::map<std::string, double>& joint_armature, const std::string& source_name)
      : model_(model), settings_(settings), joint_armature_(joint_armature), source_name_(source_name) {}

  std::string write() {
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) throw ConfigError(source_name_ + ": the robot has no root link");
    const bool root_is_world = root->name == "world";
    floating_base_ = !sim_common::isFixedBase(model_, settings_.base);

    std::ostringstream world;
    if (settings_.ground_plane) {
      // Without self-collision the robot's geoms (contype 1, conaffinity 2)
      // touch the ground (contype 2, conaffinity 1) but not each other.
      // MuJoCo takes the larger of two geoms' friction and contact dimension:
      // a frictionless, normal-only ground leaves each contact the link's own.
      world << "    <geom name=\"servoloop_ground_plane\" type=\"plane\" size=\"0 0 1\" friction=\"0 0 0\" "
               "condim=\"1\""
            << (settings_.self_collide ? "" : " contype=\"2\" conaffinity=\"1\"") << "/>\n";
    }
    if (root_is_world) {
      // The "world" link stands at the spawn pose (Gazebo's): a static body
      // there when the pose moves it, the world body itself otherwise.
      const bool placed = !settings_.base_position.isZero() ||
                          !settings_.base_orientation.normalized().isApprox(Eigen::Quaterniond::Identity());
      int depth = 2;
      if (placed) {
        world << "    <body name=\"" << kSpawnFrameBody << "\" " << basePoseAttributes() << ">\n";
        world_welded_links_.push_back(kSpawnFrameBody);
        depth = 3;
      }
      for (const auto& child : root->child_links) collectWorldWelded(*child);
      writeGeoms(*root, world, std::string(2 * depth, ' '));
      for (const auto& child : root->child_links) writeBody(*child, world, depth, /*welded_to_world=*/true);
      if (placed) world << "    </body>\n";
    } else {
      if (!floating_base_) {  // the root body is welded to the world at the spawn pose
        world_welded_links_.push_back(root->name);
        for (const auto& child : root->child_links) collectWorldWelded(*child);
      }
      writeBody(*root, world, 2, /*welded_to_world=*/!floating_base_);
    }

    const double dt = settings_.time_step_s;
    const int contacts = std::max(kMinContacts, kContactsPerBody * (body_count_ + 1));
    std::ostringstream out;
    out << "<mujoco model=\"" << xmlEscape(model_.getName()) << "\">\n"
        << "  <compiler angle=\"radian\" inertiafromgeom=\"false\""
        << (unbalanced_inertias_.empty() ? "" : " balanceinertia=\"true\"") << "/>\n"
        << "  <option timestep=\"" << number(dt) << "\" gravity=\""
        << vec3(settings_.gravity.x(), settings_.gravity.y(), settings_.gravity.z())
        << "\" integrator=\"RK4\"/>\n"
        << "  <size nconmax=\"" << contacts << "\" njmax=\""
        << contacts * kConstraintRowsPerContact + 2 * movable_joint_count_ << "\"/>\n"
        << "  <default>\n"
        << "    <joint solreflimit=\"" << number(kStopTimeConstantInSteps * dt) << " 1\" solimplimit=\""
        << kStopImpedance << "\" solreffriction=\"" << number(kStopTimeConstantInSteps * dt)
        << " 1\" solimpfriction=\"" << kStopImpedance << "\"/>\n"
        << (settings_.self_collide ? "" : "    <geom contype=\"1\" conaffinity=\"2\"/>\n")
        << "  </default>\n";
    if (!assets_.str().empty()) out << "  <asset>\n" << assets_.str() << "  </asset>\n";
    out << "  <worldbody>\n" << world.str() << "  </worldbody>\n";
    if (!excludes_.str().empty()) out << "  <contact>\n" << excludes_.str() << "  </contact>\n";
    writeMimicEqualities(out);
    out << "</mujoco>\n";
    return out.str();
  }

 private:
  // `welded_to_world`: the link's parent body is the world or welded to it.
  void writeBody(const urdf::Link& link, std::ostringstream& out, int depth, bool welded_to_world) {
    const std::string indent(2 * depth, ' ');
    const urdf::JointSharedPtr& joint = link.parent_joint;
    ++body_count_;
    out << indent << "<body name=\"" << xmlEscape(link.name) << "\"";
    if (joint) {
      out << " " << poseAttributes(joint->parent_to_joint_origin_transform);
    } else {
      out << " " << basePoseAttributes();
    }
    out << ">\n";

    bool moves = false;
    if (!joint) {  // the root link: free, or welded to the world at the spawn pose
      if (floating_base_) {
        out << indent << "  <freejoint name=\"" << xmlEscape(link.name) << "_floating_base\"/>\n";
        moves = true;
      }
    } else if (isMovable(*joint)) {
      writeJoint(*joint, out, indent + "  ");
      moves = true;
      // MuJoCo does not filter a child from a parent welded to the world; the
      // links welded to the world form one rigid base, as in the bullet backend.
      if (welded_to_world) {
        for (const std::string& static_link : world_welded_links_) {
          excludes_ << "    <exclude body1=\"" << xmlEscape(static_link) << "\" body2=\"" << xmlEscape(link.name)
                    << "\"/>\n";
        }
      }
    } else if (joint->type != urdf::Joint::FIXED) {
      throw ConfigError(source_name_ + ": joint '" + joint->name +
                        "' is floating or planar; servoloop simulates revolute, continuous, prismatic and "
                        "fixed joints only (make the link the root for a floating base)");
    }
    writeInertial(link, out, indent + "  ");
    writeGeoms(link, out, indent + "  ");

    const bool children_welded_to_world = welded_to_world && !moves;
    for (const auto& child : link.child_links) writeBody(*child, out, depth + 1, children_welded_to_world);
    out << indent << "</body>\n";
  }

  // <mimic>: q_m = offset + multiplier·q_l, as a joint equality (MuJoCo's
  // polynomial y = a0 + a1·x with both joints' reference positions at 0),
  // solved with the stiffness of the joint stops.
  void writeMimicEqualities(std::ostringstream& out) const {
    std::ostringstream equalities;
    for (const auto& [name, joint] : model_.joints_) {
      if (!joint || !joint->mimic || !isMovable(*joint)) continue;
      const urdf::JointConstSharedPtr leader = model_.getJoint(joint->mimic->joint_name);
      if (!leader || !isMovable(*leader)) {
        throw ConfigError(source_name_ + ": joint '" + name + "' <mimic joint=\"" + joint->mimic->joint_name +
                          "\">: no movable joint of that name; name a revolute, continuous or prismatic joint");
      }
      equalities << "    <joint joint1=\"" << xmlEscape(name) << "\" joint2=\"" << xmlEscape(leader->name)
                 << "\" polycoef=\"" << number(joint->mimic->offset) << " " << number(joint->mimic->multiplier)
                 << " 0 0 0\" solref=\"" << number(kStopTimeConstantInSteps * settings_.time_step_s)
                 << " 1\" solimp=\"" << kStopImpedance << "\"/>\n";
    }
    if (!equalities.str().empty()) out << "  <equality>\n" << equalities.str() << "  </equality>\n";
  }

  // pos/quat of the root link: the spawn pose of the settings.
  std::string basePoseAttributes() const {
    const Eigen::Vector3d& p = settings_.base_position;
    const Eigen::Quaterniond q = settings_.base_orientation.normalized();
    return "pos=\"" + vec3(p.x(), p.y(), p.z()) + "\" quat=\"" + number(q.w()) + " " + vec3(q.x(), q.y(), q.z()) +
           "\"";
  }

  // The links attached to the world link through fixed joints only.
  void collectWorldWelded(const urdf::Link& link) {
    if (!link.parent_joint || link.parent_joint->type != urdf::Joint::FIXED) return;
    world_welded_links_.push_back(link.name);
    for (const auto& child : link.child_links) collectWorldWelded(*child);
  }

  void writeJoint(const urdf::Joint& joint, std::ostringstream& out, const std::string& indent) {
    ++movable_joint_count_;
    const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
    out << indent << "<joint name=\"" << xmlEscape(joint.name) << "\" type=\"" << (prismatic ? "slide" : "hinge")
        << "\" pos=\"0 0 0\" axis=\"" << vec3(joint.axis.x, joint.axis.y, joint.axis.z) << "\"";
    const bool limited = joint.type != urdf::Joint::CONTINUOUS && joint.limits &&
                         std::isfinite(joint.limits->lower) && std::isfinite(joint.limits->upper) &&
                         joint.limits->lower < joint.limits->upper;
    if (limited) {
      out << " limited=\"true\" range=\"" << number(joint.limits->lower) << " " << number(joint.limits->upper) << "\"";
    } else {
      out << " limited=\"false\"";
    }
    if (joint.dynamics) {
      out << " damping=\"" << number(joint.dynamics->damping) << "\" frictionloss=\""
          << number(joint.dynamics->friction) << "\"";
    }
    const auto armature = joint_armature_.find(joint.name);
    if (armature != joint_armature_.end() && armature->second > 0.0) {
      out << " armature=\"" << number(armature->second) << "\"";
    }
    out << "/>\n";
  }

  void writeInertial(const urdf::Link& link, std::ostringstream& out, const std::string& indent) {
    if (!link.inertial || !(link.inertial->mass > 0.0)) return;
    const urdf::Inertial& inertial = *link.inertial;
    Eigen::Matrix3d inertia;
    inertia << inertial.ixx, inertial.ixy, inertial.ixz,  //
        inertial.ixy, inertial.iyy, inertial.iyz,          //
        inertial.ixz, inertial.iyz, inertial.izz;
    // MuJoCo refuses principal moments with A + B < C, which rounded values
    // in real descriptions (PR2's) break by a hair and which ODE (Gazebo)
    // accepts. MuJoCo's balanceinertia then raises the two smaller moments;
    // the link is named once.
    const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
    if (moments(0) + moments(1) < moments(2)) {
      unbalanced_inertias_.push_back(link.name);
      logger().warn(
          "{}: link '{}': principal moments {}, {}, {} break A + B >= C, which MuJoCo requires; the mujoco backend "
          "lets MuJoCo balance them (balanceinertia). Correct the <inertia> to silence this",
          source_name_, link.name, moments(0), moments(1), moments(2));
    }
    double w = 1.0, x = 0.0, y = 0.0, z = 0.0;
    inertial.origin.rotation.getQuaternion(x, y, z, w);
    // The tensor is given in the <inertial><origin> frame; MuJoCo wants it in
    // the body (link) frame when fullinertia is used: R I Rᵀ.
    const Eigen::Matrix3d rotation = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
    const Eigen::Matrix3d in_link = rotation * inertia * rotation.transpose();
    const urdf::Vector3& com = inertial.origin.position;
    out << indent << "<inertial pos=\"" << vec3(com.x, com.y, com.z) << "\" mass=\"" << number(inertial.mass)
        << "\" fullinertia=\"" << vec3(in_link(0, 0), in_link(1, 1), in_link(2, 2)) << " "
        << vec3(in_link(0, 1), in_link(0, 2), in_link(1, 2)) << "\"/>\n";
  }

  void writeGeoms(const urdf::Link& link, std::ostringstream& out, const std::string& indent) {
    std::vector<urdf::CollisionSharedPtr> collisions = link.collision_array;
    if (collisions.empty() && link.collision) collisions.push_back(link.collision);
    for (const auto& collision : collisions) {
      if (!collision || !collision->geometry) continue;
      const urdf::Geometry& geometry = *collision->geometry;
      const std::string pose = poseAttributes(collision->origin) + frictionAttributes(link);
      switch (geometry.type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(geometry);
          out << indent << "<geom type=\"box\" " << pose << " size=\""
              << vec3(box.dim.x / 2, box.dim.y / 2, box.dim.z / 2) << "\"/>\n";
          break;
        }
        case urdf::Geometry::CYLINDER: {  // both along the local z axis
          const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
          const urdf::Rotation& q = collision->origin.rotation;
          const bool wheel = sim_common::isWheelCylinder(
              link.parent_joint.get(), Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix(), cylinder.radius,
              cylinder.length);
          // A wheel's tyre profile (wheel_contact.hpp): same radius, touching in the middle plane.
          out << indent << "<geom type=\"" << (wheel ? "ellipsoid" : "cylinder") << "\" " << pose << " size=\""
              << number(cylinder.radius) << " " << (wheel ? number(cylinder.radius) + " " : std::string())
              << number(cylinder.length / 2) << "\"/>\n";
          break;
        }
        case urdf::Geometry::SPHERE:
          out << indent << "<geom type=\"sphere\" " << pose << " size=\""
              << number(static_cast<const urdf::Sphere&>(geometry).radius) << "\"/>\n";
          break;
        case urdf::Geometry::MESH:
          out << indent << "<geom type=\"mesh\" mesh=\"" << addMesh(link, static_cast<const urdf::Mesh&>(geometry))
              << "\" " << pose << "/>\n";
          break;
        default:
          break;
      }
    }
  }

  // The link's Gazebo <mu1>/<mu2> as the geom's sliding friction (MuJoCo's
  // default torsional and rolling terms, used only with condim > 3); a
  // frictionless link has normal-only contacts.
  std::string frictionAttributes(const urdf::Link& link) const {
    const double mu = sim_common::linkFriction(settings_.link_friction, link.name);
    return " friction=\"" + number(mu) + " 0.005 0.0001\"" + (mu == 0.0 ? " condim=\"1\"" : "");
  }

  std::string addMesh(const urdf::Link& link, const urdf::Mesh& mesh) {
    std::vector<Eigen::Vector3d> vertices;
    try {
      vertices = sim_common::collisionHullVertices(mesh.filename,
                                                   Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
    } catch (const ConfigError& error) {
      throw ConfigError(source_name_ + ": link '" + link.name + "' <collision> mesh: " + error.what());
    }
    const std::string name = "servoloop_mesh_" + std::to_string(mesh_count_++);
    // Scaled already (a mirroring scale included): MuJoCo gets the hull's corners.
    assets_ << "    <mesh name=\"" << name << "\" vertex=\"";
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      assets_ << (i == 0 ? "" : " ") << vec3(vertices[i].x(), vertices[i].y(), vertices[i].z());
    }
    assets_ << "\"/>\n";
    return name;
  }

  const urdf::ModelInterface& model_;
  const sim_common::SimSettings& settings_;
  const std::map<std::string, double>& joint_armature_;
  const std::string& source_name_;
  std::ostringstream assets_;
  std::ostringstream excludes_;
  std::vector<std::string> world_welded_links_;  // (not the world link itself: it is <worldbody>)
  bool floating_base_ = true;
  std::vector<std::string> unbalanced_inertias_;
  int body_count_ = 0;
  int movable_joint_count_ = 0;
  int mesh_count_ = 0;
};

}  // namespace

std::string mjcfFromUrdf(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                         const std::map<std::string, double>& joint_armature, const std::string& source_name) {
  return MjcfWriter(model, settings, joint_armature, source_name).write();
}

}  // namespace servoloop::sim_mujoco
