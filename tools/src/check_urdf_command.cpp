// `servoloop check-urdf FILE`: the offline check_urdf. Loads the URDF with
// servoloop's validation, then prints the link tree (as check_urdf does), each
// joint with its axis, limits, dynamics and soft limits, the transmissions, and
// what a simulated robot's hardware will expose: the joints' state and command
// interfaces, built the way the simulation backends build them (a joint that no
// <transmission> names gets an implicit SimpleTransmission with the effort,
// velocity and position joint interfaces).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <urdf_model/model.h>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_limits_urdf.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/simulatable_urdf.hpp"
#include "servoloop/description/xacro.hpp"
#include "servoloop/transmissions/robot_transmissions.hpp"
#include "servoloop/transmissions/transmission_parser.hpp"

namespace servoloop::cli {
namespace {

namespace hi = servoloop::hardware_interface;
namespace tr = servoloop::transmissions;
using nlohmann::ordered_json;
using servoloop::formatDouble;

struct CheckUrdfOptions {
  std::string file;
  std::vector<std::string> xacro_args;  // name:=value, for a .xacro file
  bool json = false;
};

// The link tree's deepest level (the root is level 0) that the report shows
// nested: past it the text report prints one line instead of the indentation
// (each level indents four more spaces: a 20,000-link chain would print 800 MB
// of spaces), and --json refuses (see runCheckUrdf).
constexpr std::size_t kMaxTreeDepth = 1000;

// The link tree as nested {"link", "children"}, built with an explicit stack
// (a chain of thousands of links would overflow the call stack otherwise).
// `depth` gets the deepest link's level (the root is level 0).
ordered_json linkTree(const urdf::Link& root, std::size_t& depth) {
  ordered_json tree{{"link", root.name}, {"children", ordered_json::array()}};
  depth = 0;
  struct Pending {
    const urdf::Link* link;
    ordered_json* node;  // stays valid: a node's children array is complete before its elements are visited
    std::size_t level;
  };
  std::vector<Pending> pending{{&root, &tree, 0}};
  while (!pending.empty()) {
    const Pending current = pending.back();
    pending.pop_back();
    depth = std::max(depth, current.level);
    ordered_json& children = (*current.node)["children"];
    for (const auto& child : current.link->child_links) {
      children.push_back(ordered_json{{"link", child->name}, {"children", ordered_json::array()}});
    }
    for (std::size_t i = 0; i < current.link->child_links.size(); ++i) {
      pending.push_back({current.link->child_links[i].get(), &children[i], current.level + 1});
    }
  }
  return tree;
}

// Joints in tree order (depth first from the root), as a reader follows the tree.
std::vector<const urdf::Joint*> collectJoints(const urdf::Link& root) {
  std::vector<const urdf::Joint*> joints;
  std::vector<const urdf::Link*> pending{&root};
  while (!pending.empty()) {
    const urdf::Link* link = pending.back();
    pending.pop_back();
    for (const auto& joint : link->child_joints) joints.push_back(joint.get());
    // Reversed, so the first child's subtree comes off the stack first.
    for (auto child = link->child_links.rbegin(); child != link->child_links.rend(); ++child) {
      pending.push_back(child->get());
    }
  }
  return joints;
}

ordered_json jointJson(const urdf::Joint& joint) {
  ordered_json out;
  out["name"] = joint.name;
  out["type"] = jointTypeName(joint.type);
  out["parent"] = joint.parent_link_name;
  out["child"] = joint.child_link_name;
  if (joint.type != urdf::Joint::FIXED && joint.type != urdf::Joint::FLOATING) {
    out["axis"] = {joint.axis.x, joint.axis.y, joint.axis.z};
  }
  hi::JointLimits limits;
  if (hi::getJointLimits(joint, limits)) {
    ordered_json limit;
    if (limits.has_position_limits) {
      limit["lower"] = limits.min_position;
      limit["upper"] = limits.max_position;
    }
    if (limits.has_velocity_limits) limit["velocity"] = limits.max_velocity;
    if (limits.has_effort_limits) limit["effort"] = limits.max_effort;
    if (limits.angle_wraparound) limit["wraps"] = true;
    out["limits"] = limit;
  } else {
    out["limits"] = nullptr;
  }
  if (joint.dynamics) {
    out["dynamics"] = {{"damping", joint.dynamics->damping}, {"friction", joint.dynamics->friction}};
  } else {
    out["dynamics"] = nullptr;
  }
  hi::SoftJointLimits soft;
  if (hi::getSoftJointLimits(joint, soft)) {
    out["soft_limits"] = {{"lower", soft.min_position},
                          {"upper", soft.max_position},
                          {"k_position", soft.k_position},
                          {"k_velocity", soft.k_velocity}};
  } else {
    out["soft_limits"] = nullptr;
  }
  if (joint.mimic) {
    out["mimic"] = {{"joint", joint.mimic->joint_name},
                    {"multiplier", joint.mimic->multiplier},
                    {"offset", joint.mimic->offset}};
  }
  return out;
}

ordered_json transmissionJson(const tr::TransmissionInfo& info) {
  ordered_json out;
  out["name"] = info.name;
  out["type"] = info.type;
  out["joints"] = ordered_json::array();
  for (const auto& joint : info.joints) {
    ordered_json entry{{"name", joint.name},
                       {"hardware_interfaces", joint.hardware_interfaces},
                       {"mechanical_reduction", joint.mechanical_reduction},
                       {"offset", joint.offset}};
    if (!joint.role.empty()) entry["role"] = joint.role;
    out["joints"].push_back(entry);
  }
  out["actuators"] = ordered_json::array();
  for (const auto& actuator : info.actuators) {
    ordered_json entry{{"name", actuator.name},
                       {"hardware_interfaces", actuator.hardware_interfaces},
                       {"mechanical_reduction", actuator.mechanical_reduction}};
    if (!actuator.role.empty()) entry["role"] = actuator.role;
    out["actuators"].push_back(entry);
  }
  return out;
}

// What the simulated hardware registers, per joint.
ordered_json hardwareJson(const tr::RobotTransmissions& robot) {
  ordered_json joints = ordered_json::array();
  const auto& implicit = robot.implicitTransmissionJoints();
  for (std::size_t j = 0; j < robot.numJoints(); ++j) {
    const std::string& name = robot.jointName(JointIndex(j));
    const auto& commands = robot.jointCommandInterfaces(JointIndex(j));
    ordered_json interfaces = ordered_json::array({"JointStateInterface"});
    if (commands.effort) interfaces.push_back("EffortJointInterface");
    if (commands.velocity) interfaces.push_back("VelocityJointInterface");
    if (commands.position) interfaces.push_back("PositionJointInterface");
    const bool is_implicit = std::find(implicit.begin(), implicit.end(), name) != implicit.end();
    joints.push_back(
        {{"name", name}, {"interfaces", interfaces}, {"implicit_transmission", is_implicit}});
  }
  ordered_json actuators = ordered_json::array();
  for (std::size_t a = 0; a < robot.numActuators(); ++a) {
    actuators.push_back(robot.actuatorName(ActuatorIndex(a)));
  }
  return {{"joints", joints}, {"actuators", actuators}};
}

std::string number(const ordered_json& value) { return formatDouble(value.get<double>()); }

std::string joinStrings(const ordered_json& list, const char* separator = ", ") {
  std::string text;
  for (const auto& item : list) text += (text.empty() ? "" : separator) + item.get<std::string>();
  return text;
}

// How many links hang below `node` in the tree.
std::size_t linksBelow(const ordered_json& node) {
  std::size_t count = 0;
  std::vector<const ordered_json*> pending{&node};
  while (!pending.empty()) {
    const ordered_json& current = *pending.back();
    pending.pop_back();
    for (const auto& child : current["children"]) {
      ++count;
      pending.push_back(&child);
    }
  }
  return count;
}

// check_urdf's indented tree below the root, in depth-first order, with an
// explicit stack; links deeper than kMaxTreeDepth get one line instead.
void printTree(const ordered_json& root) {
  struct Pending {
    const ordered_json* node;
    std::size_t level;  // the root is level 0, and not printed here
    std::size_t index;  // among its siblings
  };
  std::vector<Pending> pending{{&root, 0, 0}};
  while (!pending.empty()) {
    const Pending current = pending.back();
    pending.pop_back();
    const ordered_json& node = *current.node;
    if (current.level > 0) {
      std::cout << std::string(current.level * 4, ' ') << "child(" << current.index + 1
                << "):  " << node["link"].get<std::string>() << "\n";
    }
    const auto& children = node["children"];
    if (current.level == kMaxTreeDepth && !children.empty()) {
      std::cout << std::string((current.level + 1) * 4, ' ') << "... " << linksBelow(node)
                << " more link(s) below " << node["link"].get<std::string>() << " not shown: the tree is deeper than "
                << kMaxTreeDepth << " levels (the joints list below has them all)\n";
      continue;
    }
    // Reversed, so the first child and its subtree come off the stack first.
    for (std::size_t i = children.size(); i-- > 0;) pending.push_back({&children[i], current.level + 1, i});
  }
}

void printJoint(const ordered_json& joint) {
  std::cout << "  " << joint["name"].get<std::string>() << " (" << joint["type"].get<std::string>()
            << "): " << joint["parent"].get<std::string>() << " -> "
            << joint["child"].get<std::string>() << "\n";
  if (joint.contains("axis")) {
    const auto& axis = joint["axis"];
    std::cout << "      axis: [" << number(axis[0]) << ", " << number(axis[1]) << ", "
              << number(axis[2]) << "]\n";
  }
  if (joint["type"] == "fixed") return;
  std::cout << "      limits:";
  if (joint["limits"].is_null()) {
    std::cout << " none\n";
  } else {
    const auto& limits = joint["limits"];
    if (limits.contains("lower")) {
      std::cout << " position [" << number(limits["lower"]) << ", " << number(limits["upper"])
                << "],";
    } else if (limits.contains("wraps")) {
      std::cout << " position unlimited (wraps),";
    }
    std::cout << " velocity " << (limits.contains("velocity") ? number(limits["velocity"]) : "-")
              << ", effort " << (limits.contains("effort") ? number(limits["effort"]) : "-")
              << "\n";
  }
  std::cout << "      dynamics: ";
  if (joint["dynamics"].is_null()) {
    std::cout << "none\n";
  } else {
    std::cout << "damping " << number(joint["dynamics"]["damping"]) << ", friction "
              << number(joint["dynamics"]["friction"]) << "\n";
  }
  std::cout << "      soft limits: ";
  if (joint["soft_limits"].is_null()) {
    std::cout << "none\n";
  } else {
    const auto& soft = joint["soft_limits"];
    std::cout << "[" << number(soft["lower"]) << ", " << number(soft["upper"]) << "], k_position "
              << number(soft["k_position"]) << ", k_velocity " << number(soft["k_velocity"])
              << "\n";
  }
  if (joint.contains("mimic")) {
    std::cout << "      mimics " << joint["mimic"]["joint"].get<std::string>() << " (multiplier "
              << number(joint["mimic"]["multiplier"]) << ", offset "
              << number(joint["mimic"]["offset"]) << ")\n";
  }
}

void printText(const ordered_json& report) {
  std::cout << "robot name is: " << report["robot"].get<std::string>() << "\n";
  std::cout << "---------- Successfully Parsed XML ---------------\n";
  const auto& tree = report["tree"];
  std::cout << "root Link: " << tree["link"].get<std::string>() << " has "
            << tree["children"].size() << " child(ren)\n";
  printTree(tree);

  std::cout << "\njoints:\n";
  for (const auto& joint : report["joints"]) printJoint(joint);

  std::cout << "\ntransmissions:";
  if (report["transmissions"].empty()) std::cout << " none";
  std::cout << "\n";
  for (const auto& transmission : report["transmissions"]) {
    std::cout << "  " << transmission["name"].get<std::string>() << " ("
              << transmission["type"].get<std::string>() << ")\n";
    for (const auto& joint : transmission["joints"]) {
      std::cout << "      joint " << joint["name"].get<std::string>() << ": ["
                << joinStrings(joint["hardware_interfaces"]) << "], reduction "
                << number(joint["mechanical_reduction"]) << ", offset " << number(joint["offset"])
                << "\n";
    }
    for (const auto& actuator : transmission["actuators"]) {
      std::cout << "      actuator " << actuator["name"].get<std::string>() << ": ["
                << joinStrings(actuator["hardware_interfaces"]) << "], reduction "
                << number(actuator["mechanical_reduction"]) << "\n";
    }
  }

  std::cout << "\nhardware interfaces (simulation):\n";
  for (const auto& joint : report["hardware"]["joints"]) {
    std::cout << "  " << joint["name"].get<std::string>() << ": "
              << joinStrings(joint["interfaces"]);
    if (joint["implicit_transmission"].get<bool>()) {
      std::cout << "  (no <transmission>: implicit SimpleTransmission, reduction 1, actuator "
                << joint["name"].get<std::string>() << "_motor)";
    }
    std::cout << "\n";
  }
  if (report["hardware"]["joints"].empty()) std::cout << "  none (no movable joint)\n";
  std::cout << "  actuators: " << joinStrings(report["hardware"]["actuators"]) << "\n";
  if (!report["skipped"]["links"].empty()) {
    std::cout << "\nleft out (no mass, as Gazebo does): links " << joinStrings(report["skipped"]["links"])
              << "; joints " << joinStrings(report["skipped"]["joints"]) << "\n";
  }
}

std::string description(const CheckUrdfOptions& options) {
  XacroArgs args;
  for (const auto& text : options.xacro_args) args.insert(parseXacroArg(text));
  return readRobotDescription(options.file, args);
}

void runCheckUrdf(const CheckUrdfOptions& options) {
  const SimulatableUrdf simulatable = simulatableUrdf(description(options), options.file);
  const std::string& xml = simulatable.xml;
  const auto model = parseRobotModel(xml, options.file);
  const auto transmissions = tr::parseTransmissions(xml, options.file);
  tr::RobotTransmissions::Options hardware_options;
  hardware_options.implicit_simple_transmissions = true;
  hardware_options.source_name = options.file;
  const tr::RobotTransmissions hardware(*model, transmissions, hardware_options);

  ordered_json report;
  report["file"] = options.file;
  report["robot"] = model->getName();
  report["root_link"] = model->getRoot()->name;
  std::size_t tree_depth = 0;
  ordered_json tree = linkTree(*model->getRoot(), tree_depth);
  // The tree goes in last (its key keeps its place): an ordered_json object
  // is a vector of (const key, value) pairs, which a growing object copies,
  // and a copy of a deep tree recurses once per level.
  report["tree"] = nullptr;
  // nlohmann's dump recurses once per level, so a deeper tree could overflow
  // the stack. --json refuses rather than emit a flat list: a consumer reads
  // "tree" as nested {"link", "children"}, and a different shape for deep
  // trees only would surprise it more than an error that says what to do.
  if (options.json && tree_depth > kMaxTreeDepth) {
    throw ConfigError(options.file + ": the link tree is " + std::to_string(tree_depth) +
                      " links deep, deeper than the " + std::to_string(kMaxTreeDepth) +
                      " levels --json nests; run check-urdf without --json for the text report");
  }
  const std::vector<const urdf::Joint*> joints = collectJoints(*model->getRoot());
  report["joints"] = ordered_json::array();
  for (const auto* joint : joints) report["joints"].push_back(jointJson(*joint));
  report["transmissions"] = ordered_json::array();
  for (const auto& info : transmissions) report["transmissions"].push_back(transmissionJson(info));
  report["hardware"] = hardwareJson(hardware);
  report["skipped"] = {{"links", simulatable.skipped_links},
                       {"joints", simulatable.skipped_joints},
                       {"transmissions", simulatable.skipped_transmissions}};
  report["tree"] = std::move(tree);

  if (options.json) {
    std::cout << report.dump(2) << "\n";
  } else {
    printText(report);
  }
}

void addCheckUrdfCommand(CLI::App& root) {
  auto options = std::make_shared<CheckUrdfOptions>();
  CLI::App* check = root.add_subcommand(
      "check-urdf",
      "Validate a URDF and show its tree, joints, limits, transmissions and hardware interfaces");
  check->add_option("file", options->file, "URDF file, or xacro file (.xacro) to expand first")
      ->required()
      ->type_name("FILE");
  check->add_option("xacro_args", options->xacro_args, "xacro arguments for a .xacro file")->type_name("NAME:=VALUE");
  check->add_flag("--json", options->json, "Print the report as one JSON object");
  check->callback([options] { runCheckUrdf(*options); });
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(70, servoloop::cli::addCheckUrdfCommand)
