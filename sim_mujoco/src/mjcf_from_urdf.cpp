#include "servoloop/sim_mujoco/mjcf_from_urdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/xml_escape.hpp"
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
// MuJoCo's contacts are soft: a held object creeps out of a grip, a pushing
// wheel slips. Its noslip solver, run after the main one, takes the slip out
// of the friction constraints (in a world of several bodies, where objects
// are held and pushed).
constexpr int kNoslipIterations = 10;
// Friction coefficients ranked for geom priorities (frictionAttributes): in
// steps of 0.001 up to 1000.
constexpr double kFrictionRanksPerUnit = 1000.0;
constexpr double kMaxRankedFriction = 1000.0;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

std::string vec3(double x, double y, double z) { return number(x) + " " + number(y) + " " + number(z); }

// pos="x y z" quat="w x y z" of a URDF pose.
std::string poseAttributes(const urdf::Pose& pose) {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;
  pose.rotation.getQuaternion(x, y, z, w);
  return "pos=\"" + vec3(pose.position.x, pose.position.y, pose.position.z) + "\" quat=\"" + number(w) + " " +
         vec3(x, y, z) + "\"";
}

// The static body that carries a "world" root link to its spawn pose.
constexpr const char* kSpawnFrameBody = "servoloop_spawn_frame";

// How many bodies MuJoCo reads nested under <worldbody>. MuJoCo 2.2 has no
// limit of its own (its headers name none), but it reads MJCF with tinyxml2,
// which refuses (XML_ELEMENT_DEPTH_EXCEEDED) to parse the content of an
// element once that content would lie TINYXML2_MAX_ELEMENT_DEPTH levels deep.
// <mujoco> and <worldbody> take two levels and a body's content (its joint,
// inertial, geoms and child bodies) one level below the body, so at most
// TINYXML2_MAX_ELEMENT_DEPTH - 4 bodies nest: 96 with Debian's tinyxml2 9
// (limit 100), as MuJoCo 2.2.2 shows (96 nested bodies load, 97 do not).
constexpr std::size_t kMaxNestedBodies = static_cast<std::size_t>(TINYXML2_MAX_ELEMENT_DEPTH - 4);

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

class MjcfWriter {
 public:
  MjcfWriter(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
             const std::map<std::string, double>& joint_armature, const std::string& source_name,
             std::string prefix = {}, bool shared = false)
      : model_(model), settings_(settings), joint_armature_(joint_armature), source_name_(source_name),
        prefix_(std::move(prefix)), shared_(shared) {}

  // The robot's share of a world (names prefixed, no <option>, no ground).
  MjcfParts parts() {
    MjcfParts parts;
    std::ostringstream world;
    writeWorldBody(world);
    parts.worldbody = world.str();
    parts.assets = assets_.str();
    if (!settings_.self_collide) {
      // No two bodies of the robot touch (other robots' bodies do).
      for (std::size_t i = 0; i < body_names_.size(); ++i) {
        for (std::size_t j = i + 1; j < body_names_.size(); ++j) {
          parts.contact += "    <exclude body1=\"" + body_names_[i] + "\" body2=\"" + body_names_[j] + "\"/>\n";
        }
      }
    } else {
      parts.contact = excludes_.str();
    }
    std::ostringstream equalities;
    writeMimicEqualities(equalities);
    parts.equality = equalities.str();
    parts.contacts = kContactsPerBody * body_count_;
    parts.constraint_rows = parts.contacts * kConstraintRowsPerContact + 2 * movable_joint_count_;
    parts.balance_inertia = !unbalanced_inertias_.empty();
    return parts;
  }

  std::string write() {
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
    writeWorldBody(world);
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
    std::ostringstream equalities;
    writeMimicEqualities(equalities);
    if (!equalities.str().empty()) out << "  <equality>\n" << equalities.str() << "  </equality>\n";
    out << "</mujoco>\n";
    return out.str();
  }

 private:
  // The robot's bodies under <worldbody> (without the ground).
  void writeWorldBody(std::ostringstream& world) {
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) throw ConfigError(source_name_ + ": the robot has no root link");
    const bool root_is_world = root->name == "world";
    // The "world" link stands at the spawn pose (Gazebo's): a static body
    // there when the pose moves it, the world body itself otherwise.
    // In a shared world always a body: the world body's own geoms would be
    // the ground's and every robot's alike.
    const bool placed =
        root_is_world && (shared_ || !settings_.base_position.isZero() ||
                          !settings_.base_orientation.normalized().isApprox(Eigen::Quaterniond::Identity()));
    checkNestingDepth(*root, placed);
    floating_base_ = !sim_common::isFixedBase(model_, settings_.base);

    if (root_is_world) {
      int depth = 2;
      if (placed) {
        world << "    <body name=\"" << name(kSpawnFrameBody) << "\" " << basePoseAttributes() << ">\n";
        body_names_.push_back(name(kSpawnFrameBody));
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
  }

  // Refuses, before anything is written, a tree deeper than MuJoCo reads
  // (kMaxNestedBodies), naming the chain, its depth and the limit, rather
  // than leaving MuJoCo to stop at it with tinyxml2's words. `spawn_frame`:
  // a "world" root's children hang from the spawn-frame body.
  void checkNestingDepth(const urdf::Link& root, bool spawn_frame) const {
    // The link deepest below the root (the first such, depth first), and how
    // many joints lead there: from an explicit stack, as a chain can be far
    // too long for a recursion.
    const urdf::Link* deepest = &root;
    std::size_t deepest_joints = 0;
    std::vector<std::pair<const urdf::Link*, std::size_t>> stack{{&root, 0}};
    while (!stack.empty()) {
      const auto [link, joints] = stack.back();
      stack.pop_back();
      if (joints > deepest_joints) {
        deepest = link;
        deepest_joints = joints;
      }
      for (auto child = link->child_links.rbegin(); child != link->child_links.rend(); ++child) {
        stack.emplace_back(child->get(), joints + 1);
      }
    }
    // A "world" root is <worldbody> itself; any other root is the outermost body.
    const std::size_t nested_bodies = deepest_joints + (root.name == "world" ? (spawn_frame ? 1 : 0) : 1);
    if (nested_bodies <= kMaxNestedBodies) return;
    throw ConfigError(source_name_ + ": the kinematic chain from '" + root.name + "' to '" + deepest->name +
                      "' is " + std::to_string(deepest_joints) + " joints deep, which MuJoCo would read as " +
                      std::to_string(nested_bodies) + " nested bodies; MuJoCo's model compiler accepts at most " +
                      std::to_string(kMaxNestedBodies) + " nested bodies (its XML reader, tinyxml2, refuses "
                      "elements nested more than " + std::to_string(TINYXML2_MAX_ELEMENT_DEPTH) +
                      " deep); use the bullet or mock backend, or a shallower tree");
  }

  // A body whose tag is open: its link, its depth (indentation), whether its
  // child bodies hang from the world or a body welded to it, and the next of
  // its children to write.
  struct OpenBody {
    const urdf::Link* link;
    int depth;
    bool children_welded_to_world;
    std::size_t next_child;
  };

  // The body of `link` and every body below it, children in order, each
  // closed after its last child: what a recursion over the links would write,
  // with the open bodies on an explicit stack instead (a chain can be
  // thousands of links long). `welded_to_world`: the link's parent body is
  // the world or welded to it.
  void writeBody(const urdf::Link& link, std::ostringstream& out, int depth, bool welded_to_world) {
    std::vector<OpenBody> open;
    openBody(link, out, depth, welded_to_world, open);
    while (!open.empty()) {
      OpenBody& body = open.back();
      if (body.next_child < body.link->child_links.size()) {
        const urdf::Link& child = *body.link->child_links[body.next_child++];
        const int child_depth = body.depth + 1;
        const bool child_welded_to_world = body.children_welded_to_world;
        openBody(child, out, child_depth, child_welded_to_world, open);  // (may move `body`)
        continue;
      }
      out << std::string(2 * body.depth, ' ') << "</body>\n";
      open.pop_back();
    }
  }

  // Opens the body of `link` and writes what it holds besides child bodies;
  // pushes it onto `open`, whose caller writes the children and closes it.
  void openBody(const urdf::Link& link, std::ostringstream& out, int depth, bool welded_to_world,
                std::vector<OpenBody>& open) {
    const std::string indent(2 * depth, ' ');
    const urdf::JointSharedPtr& joint = link.parent_joint;
    ++body_count_;
    out << indent << "<body name=\"" << name(link.name) << "\"";
    body_names_.push_back(name(link.name));
    if (joint) {
      out << " " << poseAttributes(joint->parent_to_joint_origin_transform);
    } else {
      out << " " << basePoseAttributes();
    }
    out << ">\n";

    bool moves = false;
    if (!joint) {  // the root link: free, or welded to the world at the spawn pose
      if (floating_base_) {
        out << indent << "  <freejoint name=\"" << name(link.name + "_floating_base") << "\"/>\n";
        moves = true;
      }
    } else if (isMovable(*joint)) {
      writeJoint(*joint, out, indent + "  ");
      moves = true;
      // MuJoCo does not filter a child from a parent welded to the world; the
      // links welded to the world form one rigid base, as in the bullet backend.
      if (welded_to_world) {
        for (const std::string& static_link : world_welded_links_) {
          excludes_ << "    <exclude body1=\"" << name(static_link) << "\" body2=\"" << name(link.name)
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

    open.push_back(OpenBody{&link, depth, welded_to_world && !moves, 0});
  }

  // <mimic>: q_m = offset + multiplier·q_l, as a joint equality (MuJoCo's
  // polynomial y = a0 + a1·x with both joints' reference positions at 0),
  // solved with the stiffness of the joint stops.
  void writeMimicEqualities(std::ostringstream& equalities) const {
    for (const auto& [name, joint] : model_.joints_) {
      if (!joint || !joint->mimic || !isMovable(*joint)) continue;
      const urdf::JointConstSharedPtr leader = model_.getJoint(joint->mimic->joint_name);
      if (!leader || !isMovable(*leader)) {
        throw ConfigError(source_name_ + ": joint '" + name + "' <mimic joint=\"" + joint->mimic->joint_name +
                          "\">: no movable joint of that name; name a revolute, continuous or prismatic joint");
      }
      equalities << "    <joint joint1=\"" << this->name(name) << "\" joint2=\"" << this->name(leader->name)
                 << "\" polycoef=\"" << number(joint->mimic->offset) << " " << number(joint->mimic->multiplier)
                 << " 0 0 0\" solref=\"" << number(kStopTimeConstantInSteps * settings_.time_step_s)
                 << " 1\" solimp=\"" << kStopImpedance << "\"/>\n";
    }
  }

  // A name of the robot's in the MJCF: with the robot's prefix in a shared world.
  std::string name(const std::string& urdf_name) const { return xmlEscape(prefix_ + urdf_name); }

  // pos/quat of the root link: the spawn pose of the settings.
  std::string basePoseAttributes() const {
    const Eigen::Vector3d& p = settings_.base_position;
    const Eigen::Quaterniond q = settings_.base_orientation.normalized();
    return "pos=\"" + vec3(p.x(), p.y(), p.z()) + "\" quat=\"" + number(q.w()) + " " + vec3(q.x(), q.y(), q.z()) +
           "\"";
  }

  // `link` and the links below it attached through fixed joints only, when
  // `link` is attached by one: depth first, children in order, from an
  // explicit stack (a chain can be far too long for a recursion).
  void collectWorldWelded(const urdf::Link& link) {
    std::vector<const urdf::Link*> stack{&link};
    while (!stack.empty()) {
      const urdf::Link& next = *stack.back();
      stack.pop_back();
      if (!next.parent_joint || next.parent_joint->type != urdf::Joint::FIXED) continue;
      world_welded_links_.push_back(next.name);
      for (auto child = next.child_links.rbegin(); child != next.child_links.rend(); ++child) {
        stack.push_back(child->get());
      }
    }
  }

  void writeJoint(const urdf::Joint& joint, std::ostringstream& out, const std::string& indent) {
    ++movable_joint_count_;
    const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
    out << indent << "<joint name=\"" << name(joint.name) << "\" type=\"" << (prismatic ? "slide" : "hinge")
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
  // Two links touching slide with the smaller of their two coefficients, as
  // in the bullet backend (Gazebo's ODE): MuJoCo takes the contact's friction
  // from the geom of higher priority (the larger when equal), so the lower
  // friction gets the higher priority. The ground (priority 0, frictionless)
  // yields to every link, which keeps its own friction there.
  std::string frictionAttributes(const urdf::Link& link) const {
    const double mu = sim_common::linkFriction(settings_.link_friction, link.name);
    const long long rank = std::llround(std::clamp(mu, 0.0, kMaxRankedFriction) * kFrictionRanksPerUnit);
    const long long priority = 1 + static_cast<long long>(kMaxRankedFriction * kFrictionRanksPerUnit) - rank;
    return " friction=\"" + number(mu) + " 0.005 0.0001\" priority=\"" + std::to_string(priority) + "\"" +
           (mu == 0.0 ? " condim=\"1\"" : "");
  }

  std::string addMesh(const urdf::Link& link, const urdf::Mesh& mesh) {
    std::vector<Eigen::Vector3d> vertices;
    try {
      vertices = sim_common::collisionHullVertices(mesh.filename,
                                                   Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
    } catch (const ConfigError& error) {
      throw ConfigError(source_name_ + ": link '" + link.name + "' <collision> mesh: " + error.what());
    }
    const std::string name = prefix_ + "servoloop_mesh_" + std::to_string(mesh_count_++);
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
  std::string prefix_;                  // before every name (a robot in a shared world)
  bool shared_ = false;
  std::vector<std::string> body_names_;  // as written
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

std::string mjcfOfWorld(const hardware_interface::SimulatedWorldSettings& settings,
                        const std::vector<const MjcfParts*>& robots) {
  int contacts = kMinContacts;
  int rows = 0;
  bool balance = false;
  std::string assets, bodies, contact, equality;
  for (const MjcfParts* robot : robots) {
    contacts += robot->contacts;
    rows += robot->constraint_rows;
    balance |= robot->balance_inertia;
    assets += robot->assets;
    bodies += robot->worldbody;
    contact += robot->contact;
    equality += robot->equality;
  }
  rows += (kMinContacts)*kConstraintRowsPerContact;
  const double dt = settings.time_step_s;
  std::ostringstream out;
  out << "<mujoco model=\"servoloop_world\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"" << (balance ? " balanceinertia=\"true\"" : "")
      << "/>\n"
      << "  <option timestep=\"" << number(dt) << "\" gravity=\""
      << vec3(settings.gravity[0], settings.gravity[1], settings.gravity[2]) << "\" integrator=\"RK4\" noslip_iterations=\""
      << kNoslipIterations << "\"/>\n"
      << "  <size nconmax=\"" << contacts << "\" njmax=\"" << rows << "\"/>\n"
      << "  <default>\n"
      << "    <joint solreflimit=\"" << number(kStopTimeConstantInSteps * dt) << " 1\" solimplimit=\""
      << kStopImpedance << "\" solreffriction=\"" << number(kStopTimeConstantInSteps * dt)
      << " 1\" solimpfriction=\"" << kStopImpedance << "\"/>\n"
      << "  </default>\n";
  if (!assets.empty()) out << "  <asset>\n" << assets << "  </asset>\n";
  out << "  <worldbody>\n";
  if (settings.ground_plane) {
    // As for one robot: a frictionless, normal-only ground leaves each
    // contact the link's own friction (MuJoCo takes the larger of two).
    out << "    <geom name=\"servoloop_ground_plane\" type=\"plane\" size=\"0 0 1\" friction=\"0 0 0\" "
           "condim=\"1\"/>\n";
  }
  out << bodies << "  </worldbody>\n";
  if (!contact.empty()) out << "  <contact>\n" << contact << "  </contact>\n";
  if (!equality.empty()) out << "  <equality>\n" << equality << "  </equality>\n";
  out << "</mujoco>\n";
  return out.str();
}

MjcfParts mjcfPartsFromUrdf(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                            const std::map<std::string, double>& joint_armature, const std::string& source_name,
                            const std::string& prefix) {
  return MjcfWriter(model, settings, joint_armature, source_name, prefix, true).parts();
}

}  // namespace servoloop::sim_mujoco
