#pragma once
// URDF → MJCF, written by servoloop rather than MuJoCo's own URDF importer:
// that importer drops <dynamics>, transmissions and anything it does not know
// without a word, while this writer maps every element the simulation uses
// and refuses what it cannot map.
//
// What the generated model contains:
//  - one <body> per URDF link, placed at its joint's <origin> in the parent
//    link's frame (so the body frame is the URDF link frame). A link attached
//    by a fixed joint is a body without a joint: MuJoCo welds it to its parent
//    and merges its mass. When the root link is "world", its children hang
//    from <worldbody> (fixed base); otherwise the root body gets a free joint;
//  - <inertial>: mass, centre of mass and the full inertia tensor rotated
//    into the link frame (MuJoCo does not accept an orientation together with
//    fullinertia);
//  - revolute → hinge, prismatic → slide, continuous → unlimited hinge, axis
//    in the link frame; a finite lower < upper becomes range + limited with a
//    stiff reference (time constant 2·time step, MuJoCo's smallest) so a stop
//    holds against the full effort; <dynamics damping> → damping,
//    <dynamics friction> → frictionloss; armature = the reflected rotor
//    inertia the caller gives per joint;
//  - <collision> box, cylinder, sphere, and meshes: the corners of their
//    bounded convex hull (sim_common/collision_mesh.hpp), scaled, go inline
//    and MuJoCo collides with their hull. A mesh that cannot be read is an
//    error naming the link and the file;
//  - a link never collides with its parent body: MuJoCo filters parent/child
//    pairs itself except when the parent is welded to the world, for which
//    <contact><exclude> pairs are written;
//  - <option>: time step, gravity, RK4 integrator (see mujoco_physics.hpp);
//    a plane z = 0 in <worldbody> when settings.ground_plane.
#include <map>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "servoloop/hardware_interface/simulated_world.hpp"
#include "servoloop/sim_common/sim_settings.hpp"

namespace servoloop::sim_mujoco {

// Non-real-time. `joint_armature`: joint name → inertia (kg·m², or kg for a
// prismatic joint) added to that joint's own (MuJoCo's armature); joints not
// listed get none. `source_name` names the URDF in errors. Throws
// servoloop::ConfigError for what cannot be mapped (floating or planar joints,
// unreadable or flat collision meshes), naming the joint or link.
std::string mjcfFromUrdf(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                         const std::map<std::string, double>& joint_armature, const std::string& source_name);

// A robot's share of a world holding several (MujocoWorld): the MJCF of its
// bodies with every name prefixed, without the world's <option>, defaults and
// ground. Its bodies touch other robots' (MuJoCo's default contype and
// conaffinity); without self-collision, <exclude> pairs keep them from
// touching each other.
struct MjcfParts {
  std::string assets;     // <asset> content
  std::string worldbody;  // <worldbody> content
  std::string contact;    // <contact> content
  std::string equality;   // <equality> content
  int contacts = 0;          // contact capacity it needs
  int constraint_rows = 0;   // constraint rows it needs
  bool balance_inertia = false;
};

// Non-real-time. As mjcfFromUrdf, for a robot of a shared world; `prefix`
// comes before every name (bodies, joints, meshes).
MjcfParts mjcfPartsFromUrdf(const urdf::ModelInterface& model, const sim_common::SimSettings& settings,
                            const std::map<std::string, double>& joint_armature, const std::string& source_name,
                            const std::string& prefix);

// Non-real-time. The MJCF of a world holding `robots`: the world's <option>
// (time step, gravity, RK4), joint defaults, capacity for every robot's
// contacts, the ground plane, and each robot's share.
std::string mjcfOfWorld(const hardware_interface::SimulatedWorldSettings& settings,
                        const std::vector<const MjcfParts*>& robots);

}  // namespace servoloop::sim_mujoco
