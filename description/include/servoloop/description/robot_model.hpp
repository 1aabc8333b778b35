#pragma once
// servoloop's one way to load a URDF: urdfdom parsing plus the checks urdfdom
// does not make, so every backend sees a model it can simulate or drive.
// Non-real-time only (reads files, allocates, throws).
#include <memory>
#include <string>

#include <urdf_model/model.h>

#include "servoloop/description/xacro.hpp"

namespace servoloop {

// Reads the URDF file at `path` (a .xacro file is expanded with `args` first),
// leaves out what cannot be simulated the way
// Gazebo does (simulatableUrdf: massless moving links, with a warning) and
// validates the rest; see parseRobotModel for what is checked. Throws
// ConfigError if the file is missing or unreadable.
std::shared_ptr<const urdf::ModelInterface> loadRobotModelFile(const std::string& path, const XacroArgs& args = {});

// Parses and validates URDF text. `source_name` names the input in every error
// message (normally the file path); relative mesh paths resolve against its
// folder, or against the current directory when it has none.
//
// Throws servoloop::ConfigError, with a message naming `source_name`, the
// element at fault and the fix, when:
//   - the text is not XML, its root is not <robot>, or urdfdom rejects it
//     (urdfdom's own console messages are captured into the error);
//   - there is no <link>, a joint names an unknown link or has an unknown or
//     missing type, a link has two parents, there are several roots, or the
//     joints form a kinematic cycle;
//   - a number in a link or joint (origins, axes, limits, dynamics, mass,
//     inertia, geometry sizes, mesh scale) is not finite;
//   - a link moved by a non-fixed joint has no <inertial>, a mass <= 0 or an
//     inertia tensor that is not positive definite; any link has mass < 0;
//   - a collision mesh file does not exist (a missing visual mesh is one
//     warning: no backend draws it).
//
// Mesh filenames in the returned model are rewritten to absolute paths:
// relative paths resolve against the URDF's folder; `file://` URIs are taken as
// paths (relative ones against the URDF's folder); `package://<pkg>/<rest>` is
// looked up as <dir>/<pkg>/<rest> for every <dir> in ROS_PACKAGE_PATH, then for
// every ancestor folder of the URDF that is itself named <pkg> or contains <pkg>.
std::shared_ptr<const urdf::ModelInterface> parseRobotModel(const std::string& xml,
                                                            const std::string& source_name);

// A joint type as the URDF writes it ("revolute", "continuous", "prismatic",
// "floating", "planar", "fixed"); "unknown" for urdf::Joint::UNKNOWN.
const char* jointTypeName(int type);

// urdfdom's parse alone, its console output captured rather than printed:
// throws ConfigError naming source_name when urdfdom returns no model; with
// report_warnings, its warnings and the errors it recovered from (an element
// it leaves out) are logged as warnings, except an <inertial> it could not read
// (its link would weigh nothing), which throws ConfigError naming the link and
// urdfdom's reason. The one way servoloop calls urdfdom.
// The model (this one and parseRobotModel's) frees its links one by one, not
// down the tree by recursion, so a chain of any length is freed safely; a
// link kept beyond its model has lost its child_links then.
std::shared_ptr<urdf::ModelInterface> parseUrdfWithUrdfdom(const std::string& xml, const std::string& source_name,
                                                          bool report_warnings);

}  // namespace servoloop
