#include "servoloop/transmissions/transmission_parser.hpp"

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/xml_error_text.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/transmissions/differential_transmission.hpp"
#include "servoloop/transmissions/four_bar_linkage_transmission.hpp"
#include "servoloop/transmissions/simple_transmission.hpp"
#include "urdf_joint_kind.hpp"

namespace servoloop::transmissions {
namespace {

constexpr std::string_view kHardwareInterfacePrefix = "hardware_interface/";
constexpr std::string_view kTransmissionPrefix = "transmission_interface/";
constexpr std::array<std::string_view, 4> kJointInterfaces = {
    "EffortJointInterface", "VelocityJointInterface", "PositionJointInterface",
    "JointStateInterface"};
constexpr std::array<std::string_view, 4> kActuatorInterfaces = {
    "EffortActuatorInterface", "VelocityActuatorInterface", "PositionActuatorInterface", "ActuatorStateInterface"};

// What each transmission type needs from its <joint> and <actuator> elements.
struct TypeRule {
  const char* type;
  const char* short_name;
  std::size_t num_joints;
  std::size_t num_actuators;
  bool needs_roles;  // joint1/joint2 and actuator1/actuator2 decide the order
};
constexpr std::array<TypeRule, 3> kTypeRules = {{
    {kSimpleTransmissionType, "SimpleTransmission", 1, 1, false},
    {kDifferentialTransmissionType, "DifferentialTransmission", 2, 2, true},
    {kFourBarLinkageTransmissionType, "FourBarLinkageTransmission", 2, 2, true},
}};

const TypeRule* findTypeRule(const std::string& type) {
  for (const TypeRule& rule : kTypeRules) {
    if (type == rule.type) return &rule;
  }
  return nullptr;
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return std::string(text.substr(first, last - first + 1));
}

std::string elementText(const tinyxml2::XMLElement* element) {
  return element != nullptr && element->GetText() != nullptr ? trim(element->GetText()) : "";
}

std::string withoutPrefix(std::string text, std::string_view prefix) {
  if (text.compare(0, prefix.size(), prefix) == 0) text.erase(0, prefix.size());
  return text;
}

// Locale-independent, whole-string, finite numbers only.
std::optional<double> parseNumber(const std::string& text) {
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::string movableJointList(const urdf::ModelInterface& robot) {
  std::string names;
  for (const auto& [name, joint] : robot.joints_) {
    if (joint && detail::isSingleDofMovable(*joint)) names += (names.empty() ? "" : ", ") + name;
  }
  return names.empty() ? "none" : names;
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

std::vector<std::string> commandInterfaceNames(const TransmissionJointInfo& joint) {
  std::vector<std::string> commands;
  for (const auto& iface : joint.hardware_interfaces) {
    if (iface != "JointStateInterface") commands.push_back(iface);
  }
  std::sort(commands.begin(), commands.end());
  commands.erase(std::unique(commands.begin(), commands.end()), commands.end());
  return commands;
}

// Collects every problem of every transmission so one run reports them all.
class Problems {
 public:
  explicit Problems(std::string source_name) : source_name_(std::move(source_name)) {}

  void setTransmission(std::string label) { label_ = std::move(label); }
  void add(const std::string& problem_and_fix) {
    lines_.push_back(source_name_ + ": transmission " + label_ + ": " + problem_and_fix);
  }
  bool empty() const { return lines_.empty(); }

  [[noreturn]] void raise() const {
    std::string message;
    for (const auto& line : lines_) message += (message.empty() ? "" : "\n") + line;
    throw ConfigError(message);
  }

 private:
  std::string source_name_;
  std::string label_;
  std::vector<std::string> lines_;
};

// Reads an optional numeric child; reports a non-number or (for reductions) a zero.
void readNumber(const tinyxml2::XMLElement* parent, const char* tag, const std::string& owner,
                bool is_reduction, double& value, Problems& problems) {
  const tinyxml2::XMLElement* element = parent->FirstChildElement(tag);
  if (element == nullptr) return;
  const std::string text = elementText(element);
  const std::optional<double> number = parseNumber(text);
  if (!number) {
    problems.add(owner + ": <" + tag + "> '" + text +
                 "' is not a number; write a finite decimal number such as " +
                 (is_reduction ? "50" : "0.5"));
    return;
  }
  if (is_reduction && *number == 0.0) {
    problems.add(owner + ": <" + tag +
                 "> is 0; a reduction must be non-zero (1 for a direct drive, negative to "
                 "reverse the direction)");
    return;
  }
  value = *number;
}

std::vector<std::string> readHardwareInterfaces(const tinyxml2::XMLElement* parent,
                                                const std::string& owner, bool validate_joint_names,
                                                Problems& problems) {
  std::vector<std::string> interfaces;
  for (auto* element = parent->FirstChildElement("hardwareInterface"); element != nullptr;
       element = element->NextSiblingElement("hardwareInterface")) {
    std::string name = withoutPrefix(elementText(element), kHardwareInterfacePrefix);
    if (name.empty()) {
      problems.add(owner +
                   " has an empty <hardwareInterface>; write e.g. "
                   "<hardwareInterface>hardware_interface/EffortJointInterface"
                   "</hardwareInterface>");
      continue;
    }
    if (validate_joint_names && std::find(kJointInterfaces.begin(), kJointInterfaces.end(), name) ==
                                    kJointInterfaces.end()) {
      problems.add(owner + ": <hardwareInterface> '" + name +
                   "' is not supported; use EffortJointInterface, VelocityJointInterface, "
                   "PositionJointInterface or JointStateInterface");
      continue;
    }
    interfaces.push_back(std::move(name));
  }
  return interfaces;
}

// What earlier transmissions use: to merge the transmissions of a joint that
// has one per hardware interface, and to report a joint, an actuator or a
// name used twice.
struct UsedNames {
  std::map<std::string, std::size_t> joint_home;      // joint → its transmission's place in the result
  std::map<std::string, std::string> actuator_owner;  // actuator → its transmission's label
  std::map<std::string, int> transmission_count;
};

// What the parse notes rather than refuses: joints whose one-per-interface
// transmissions were merged, and actuators without a <mechanicalReduction>.
struct ParseNotes {
  std::vector<std::string> merged_joints;  // "j1 (PositionJointInterface, VelocityJointInterface)"
  std::vector<std::string> unreduced_actuators;
};

// The pre-2015 form names the interfaces in the <actuator> only. ros_control
// still takes them for the joint, with a deprecation warning; so does
// servoloop. True when the first <actuator> had interfaces to take.
bool takeLegacyActuatorInterfaces(const tinyxml2::XMLElement* transmission, const std::string& owner,
                                  const std::string& label, const std::string& source_name,
                                  TransmissionJointInfo& joint, Problems& problems) {
  const tinyxml2::XMLElement* actuator = transmission->FirstChildElement("actuator");
  if (actuator == nullptr || actuator->FirstChildElement("hardwareInterface") == nullptr) return false;
  joint.hardware_interfaces = readHardwareInterfaces(actuator, owner, true, problems);
  std::string names;
  for (const auto& name : joint.hardware_interfaces) names += (names.empty() ? "" : ", ") + name;
  logger().warn(
      "{}: transmission {}: {} has no <hardwareInterface>; taking the one(s) of its <actuator> ({}), the "
      "deprecated pre-2015 form; move <hardwareInterface>hardware_interface/...</hardwareInterface> into the "
      "<joint> element",
      source_name, label, owner, names);
  return true;
}

void readJoints(const tinyxml2::XMLElement* transmission, const urdf::ModelInterface& robot,
                const std::string& label, const std::string& source_name, TransmissionInfo& info,
                Problems& problems) {
  for (auto* element = transmission->FirstChildElement("joint"); element != nullptr;
       element = element->NextSiblingElement("joint")) {
    TransmissionJointInfo joint;
    const char* name = element->Attribute("name");
    joint.name = name != nullptr ? trim(name) : "";
    if (joint.name.empty()) {
      problems.add("a <joint> has no name attribute; add name=\"<one of the robot's joints: " +
                   movableJointList(robot) + ">\"");
      info.joints.push_back(std::move(joint));
      continue;
    }
    const std::string owner = "joint '" + joint.name + "'";

    joint.hardware_interfaces = readHardwareInterfaces(element, owner, true, problems);
    if (element->FirstChildElement("hardwareInterface") == nullptr &&
        !takeLegacyActuatorInterfaces(transmission, owner, label, source_name, joint, problems)) {
      problems.add(owner +
                   " has no <hardwareInterface>; add e.g. "
                   "<hardwareInterface>hardware_interface/EffortJointInterface"
                   "</hardwareInterface>");
    }
    joint.role = elementText(element->FirstChildElement("role"));
    readNumber(element, "mechanicalReduction", owner, true, joint.mechanical_reduction, problems);
    readNumber(element, "offset", owner, false, joint.offset, problems);

    const urdf::JointConstSharedPtr urdf_joint = robot.getJoint(joint.name);
    if (!urdf_joint) {
      problems.add(owner + " is not a joint of robot '" + robot.getName() +
                   "'; fix the name (the robot's movable joints: " + movableJointList(robot) + ")");
    } else if (!detail::isSingleDofMovable(*urdf_joint)) {
      problems.add(owner +
                   " is not a revolute, continuous or prismatic joint; a transmission drives "
                   "one movable degree of freedom, so remove the <joint> or change the joint type");
    }
    if (std::any_of(info.joints.begin(), info.joints.end(),
                    [&](const TransmissionJointInfo& other) { return other.name == joint.name; })) {
      problems.add(owner + " is listed twice; list each joint once");
    }
    info.joints.push_back(std::move(joint));
  }
}

void readActuators(const tinyxml2::XMLElement* transmission, const std::string& label,
                   const std::string& source_name, TransmissionInfo& info, ParseNotes& notes,
                   Problems& problems) {
  for (auto* element = transmission->FirstChildElement("actuator"); element != nullptr;
       element = element->NextSiblingElement("actuator")) {
    TransmissionActuatorInfo actuator;
    const char* name = element->Attribute("name");
    actuator.name = name != nullptr ? trim(name) : "";
    if (actuator.name.empty()) {
      problems.add("an <actuator> has no name attribute; add name=\"<motor name>\"");
      info.actuators.push_back(std::move(actuator));
      continue;
    }
    const std::string owner = "actuator '" + actuator.name + "'";

    actuator.hardware_interfaces = readHardwareInterfaces(element, owner, false, problems);
    for (const std::string& interface : actuator.hardware_interfaces) {
      if (std::find(kJointInterfaces.begin(), kJointInterfaces.end(), interface) == kJointInterfaces.end() &&
          std::find(kActuatorInterfaces.begin(), kActuatorInterfaces.end(), interface) == kActuatorInterfaces.end()) {
        logger().warn("{}: transmission {}: {}: <hardwareInterface> '{}' is not an interface ros_control knows "
                      "(an actuator's are EffortActuatorInterface, VelocityActuatorInterface, "
                      "PositionActuatorInterface, or a joint interface in the pre-2015 form); it is ignored",
                      source_name, label, owner, interface);
      }
    }
    actuator.role = elementText(element->FirstChildElement("role"));
    if (element->FirstChildElement("mechanicalReduction") == nullptr) {
      // gazebo_ros_control drives the joint itself, as a reduction of 1
      // would; franka_description's transmissions leave it out so.
      if (std::find(notes.unreduced_actuators.begin(), notes.unreduced_actuators.end(), actuator.name) ==
          notes.unreduced_actuators.end()) {
        notes.unreduced_actuators.push_back(actuator.name);
      }
    } else {
      readNumber(element, "mechanicalReduction", owner, true, actuator.mechanical_reduction,
                 problems);
    }
    if (std::any_of(info.actuators.begin(), info.actuators.end(),
                    [&](const TransmissionActuatorInfo& other) { return other.name == actuator.name; })) {
      problems.add(owner + " is listed twice; list each actuator once");
    }
    info.actuators.push_back(std::move(actuator));
  }
}

// Checks roles are exactly {prefix1, prefix2}; on success orders items by role.
template <class Item>
void orderByRole(std::vector<Item>& items, const char* kind, const TypeRule& rule,
                 Problems& problems) {
  const std::string role1 = std::string(kind) + "1";
  const std::string role2 = std::string(kind) + "2";
  bool roles_ok = true;
  for (const Item& item : items) {
    const std::string owner = std::string(kind) + " '" + item.name + "'";
    if (item.role.empty()) {
      problems.add(owner + " has no <role>; a " + rule.short_name + " needs <role>" + role1 +
                   "</role> on one " + kind + " and <role>" + role2 + "</role> on the other");
      roles_ok = false;
    } else if (item.role != role1 && item.role != role2) {
      problems.add(owner + " has role '" + item.role + "'; use " + role1 + " or " + role2);
      roles_ok = false;
    }
  }
  if (!roles_ok || items.size() != 2) return;
  if (items[0].role == items[1].role) {
    problems.add(std::string("both ") + kind + "s have role '" + items[0].role + "'; give one " +
                 role1 + " and the other " + role2);
    return;
  }
  if (items[0].role == role2) std::swap(items[0], items[1]);
}

void validateForType(TransmissionInfo& info, const TypeRule& rule, Problems& problems) {
  if (info.joints.size() != rule.num_joints) {
    problems.add(std::string(rule.short_name) + " needs exactly " +
                 std::to_string(rule.num_joints) + " <joint>, found " +
                 std::to_string(info.joints.size()) +
                 (rule.num_joints == 1 ? "; use one <transmission> per joint"
                                       : "; list both joints, with roles joint1 and joint2"));
  }
  if (info.actuators.size() != rule.num_actuators) {
    problems.add(
        std::string(rule.short_name) + " needs exactly " + std::to_string(rule.num_actuators) +
        " <actuator>, found " + std::to_string(info.actuators.size()) +
        (rule.num_actuators == 1 ? "; give it one <actuator> with a <mechanicalReduction>"
                                 : "; list both actuators, with roles actuator1 and actuator2"));
  }
  if (!rule.needs_roles) return;
  orderByRole(info.joints, "joint", rule, problems);
  orderByRole(info.actuators, "actuator", rule, problems);

  // A coupled mechanism cannot take an effort on one joint and a position on the other.
  if (info.joints.size() == 2 &&
      commandInterfaceNames(info.joints[0]) != commandInterfaceNames(info.joints[1])) {
    problems.add("joints '" + info.joints[0].name + "' (" +
                 join(commandInterfaceNames(info.joints[0])) + ") and '" + info.joints[1].name +
                 "' (" + join(commandInterfaceNames(info.joints[1])) +
                 ") name different command interfaces; a " + rule.short_name +
                 " couples its joints, so give both the same <hardwareInterface> list");
  }
}

bool isOneJointSimple(const TransmissionInfo& info) {
  return info.type == kSimpleTransmissionType && info.joints.size() == 1 && info.actuators.size() == 1;
}

// A SimpleTransmission for a joint an earlier SimpleTransmission drives, as
// franka_description declares one per hardware interface (its Gazebo plugin
// and gazebo_ros_control accept that): the earlier one takes its interfaces,
// if it adds any and both agree on the reduction and offset.
void mergeInto(TransmissionInfo& earlier, const TransmissionInfo& info, const std::string& earlier_label,
               UsedNames& used, ParseNotes& notes, Problems& problems) {
  TransmissionJointInfo& kept = earlier.joints[0];
  const TransmissionJointInfo& joint = info.joints[0];
  const std::string owner = "joint '" + joint.name + "'";
  std::vector<std::string> added;
  for (const std::string& name : joint.hardware_interfaces) {
    if (std::find(kept.hardware_interfaces.begin(), kept.hardware_interfaces.end(), name) ==
            kept.hardware_interfaces.end() &&
        std::find(added.begin(), added.end(), name) == added.end()) {
      added.push_back(name);
    }
  }
  const double kept_reduction = earlier.actuators[0].mechanical_reduction;
  const double reduction = info.actuators[0].mechanical_reduction;
  if (added.empty()) {
    problems.add(owner + " is already driven by transmission " + earlier_label + " with the same <hardwareInterface> (" +
                 join(joint.hardware_interfaces) +
                 "); remove one of the two, or give this one another interface (a joint may have one "
                 "SimpleTransmission per interface)");
  } else if (reduction != kept_reduction || joint.offset != kept.offset) {
    const bool reductions_differ = reduction != kept_reduction;
    problems.add(owner + " is also driven by transmission " + earlier_label + ", with " +
                 (reductions_differ ? "<mechanicalReduction> " + fmt::format("{}", kept_reduction) + " there and " +
                                          fmt::format("{}", reduction)
                                    : "<offset> " + fmt::format("{}", kept.offset) + " there and " +
                                          fmt::format("{}", joint.offset)) +
                 " here; the transmissions of one joint (one per interface) drive the same motor, so give them the "
                 "same " + (reductions_differ ? "<mechanicalReduction>" : "<offset>"));
  } else {
    kept.hardware_interfaces.insert(kept.hardware_interfaces.end(), added.begin(), added.end());
    auto& actuator_interfaces = earlier.actuators[0].hardware_interfaces;
    for (const std::string& name : info.actuators[0].hardware_interfaces) {
      if (std::find(actuator_interfaces.begin(), actuator_interfaces.end(), name) == actuator_interfaces.end()) {
        actuator_interfaces.push_back(name);
      }
    }
    const std::string entry_prefix = joint.name + " (";
    const auto entry = std::find_if(notes.merged_joints.begin(), notes.merged_joints.end(),
                                    [&](const std::string& e) { return e.rfind(entry_prefix, 0) == 0; });
    const std::string text = entry_prefix + join(kept.hardware_interfaces) + ")";
    if (entry != notes.merged_joints.end()) {
      *entry = text;
    } else {
      notes.merged_joints.push_back(text);
    }
  }
  // The merged transmission keeps the earlier one's actuator; this one's name
  // stays taken, as the same motor. It must not be another transmission's.
  const std::string& actuator = info.actuators[0].name;
  const auto [it, inserted] = used.actuator_owner.emplace(actuator, earlier_label);
  if (!inserted && it->second != earlier_label) {
    problems.add("actuator '" + actuator + "' is already used by transmission " + it->second +
                 "; give each actuator a unique name");
  }
}

// Adds a parsed transmission to the result, or merges it into an earlier
// one driving the same joint; reports joints, actuators and names used twice.
void placeTransmission(TransmissionInfo info, const std::string& label, std::vector<TransmissionInfo>& infos,
                       std::vector<std::string>& labels, UsedNames& used, ParseNotes& notes, Problems& problems) {
  bool shared_joint = false;
  for (const TransmissionJointInfo& joint : info.joints) {
    const auto home = used.joint_home.find(joint.name);
    if (joint.name.empty() || home == used.joint_home.end()) continue;
    shared_joint = true;
    TransmissionInfo& earlier = infos[home->second];
    if (isOneJointSimple(info) && isOneJointSimple(earlier)) {
      mergeInto(earlier, info, labels[home->second], used, notes, problems);
    } else {
      problems.add("joint '" + joint.name + "' is already driven by transmission " + labels[home->second] +
                   "; only SimpleTransmissions (one per hardware interface) may share a joint, so drive it from "
                   "one transmission");
    }
  }
  if (shared_joint) return;
  if (!info.name.empty() && ++used.transmission_count[info.name] == 2) {
    problems.add("the name is used by more than one <transmission>; give each a unique name");
  }
  for (const TransmissionJointInfo& joint : info.joints) {
    if (!joint.name.empty()) used.joint_home.emplace(joint.name, infos.size());
  }
  for (const TransmissionActuatorInfo& actuator : info.actuators) {
    if (actuator.name.empty()) continue;
    const auto [it, inserted] = used.actuator_owner.emplace(actuator.name, label);
    if (!inserted) {
      problems.add("actuator '" + actuator.name + "' is already used by transmission " + it->second +
                   "; give each actuator a unique name");
    }
  }
  infos.push_back(std::move(info));
  labels.push_back(label);
}

// The notes of one parse, a line each: merged transmissions and actuators
// taken as direct drives (the first few named, and how many there are).
void logNotes(const ParseNotes& notes, const std::string& source_name) {
  constexpr std::size_t kNamed = 4;
  auto some = [&](const std::vector<std::string>& items) {
    std::string text;
    for (std::size_t i = 0; i < items.size() && i < kNamed; ++i) text += (i == 0 ? "" : ", ") + items[i];
    if (items.size() > kNamed) text += fmt::format(" and {} more", items.size() - kNamed);
    return text;
  };
  if (!notes.merged_joints.empty()) {
    logger().info(
        "{}: {} {} one SimpleTransmission per hardware interface; each joint's are merged into one offering all "
        "of them, with the first one's actuator (as franka_gazebo and gazebo_ros_control accept them): {}",
        source_name, notes.merged_joints.size() == 1 ? "joint" : fmt::format("{} joints", notes.merged_joints.size()),
        notes.merged_joints.size() == 1 ? "has" : "have", some(notes.merged_joints));
  }
  if (!notes.unreduced_actuators.empty()) {
    logger().info(
        "{}: {} {} without <mechanicalReduction> {} taken as a direct drive (reduction 1), as gazebo_ros_control "
        "drives {}; add <mechanicalReduction> to say otherwise",
        source_name, notes.unreduced_actuators.size() == 1 ? "actuator" : "actuators",
        some(notes.unreduced_actuators), notes.unreduced_actuators.size() == 1 ? "is" : "are",
        notes.unreduced_actuators.size() == 1 ? "it" : "them");
  }
}

// True for pr2_mechanism_model's transmissions, which predate ros_control: a
// type="..." attribute and no <hardwareInterface> in any joint or actuator.
bool isPr2MechanismForm(const tinyxml2::XMLElement* transmission) {
  if (transmission->Attribute("type") == nullptr || transmission->FirstChildElement("type") != nullptr) return false;
  for (const char* tag : {"joint", "actuator"}) {
    for (auto* e = transmission->FirstChildElement(tag); e != nullptr; e = e->NextSiblingElement(tag)) {
      if (e->FirstChildElement("hardwareInterface") != nullptr) return false;
    }
  }
  return true;
}

// The type as written: the <type> child, else the legacy type="..." attribute.
std::string readType(const tinyxml2::XMLElement* transmission) {
  std::string type = elementText(transmission->FirstChildElement("type"));
  if (type.empty() && transmission->Attribute("type") != nullptr) {
    type = trim(transmission->Attribute("type"));
  }
  return type;
}

// "SimpleTransmission" and "transmission_interface/SimpleTransmission" name the same type.
std::string withTransmissionPrefix(const std::string& type) {
  if (type.empty() || type.find('/') != std::string::npos) return type;
  return std::string(kTransmissionPrefix) + type;
}

// One warning naming the transmissions written in pr2_mechanism_model's form
// (the first few of them, and how many there are).
void warnPr2MechanismForm(const std::vector<std::string>& labels, const std::vector<std::string>& types,
                          const std::string& source_name) {
  if (labels.empty()) return;
  constexpr std::size_t kNamed = 4;
  std::string names;
  for (std::size_t i = 0; i < labels.size() && i < kNamed; ++i) names += (i == 0 ? "" : ", ") + labels[i];
  if (labels.size() > kNamed) names += fmt::format(" and {} more", labels.size() - kNamed);
  std::string type_list;
  for (const std::string& type : types) type_list += (type_list.empty() ? "" : "\", type=\"") + type;
  logger().warn(
      "{}: {} {}: the pre-ros_control form (type=\"{}\" attribute, no <hardwareInterface>) is skipped; "
      "{} joints get the implicit SimpleTransmission (reduction 1; effort, velocity or position joint "
      "interface) when simulated. To keep {}, write <type>transmission_interface/SimpleTransmission</type> "
      "and put in each <joint> the interface its controller claims, e.g. "
      "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface> (or "
      "VelocityJointInterface, PositionJointInterface)",
      source_name, labels.size() == 1 ? "transmission" : fmt::format("{} transmissions", labels.size()), names,
      type_list,
      labels.size() == 1 ? "its" : "their", labels.size() == 1 ? "it" : "them");
}

}  // namespace

std::vector<TransmissionInfo> parseTransmissions(const std::string& urdf_xml,
                                                 const std::string& source_name) {
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) {
    throw ConfigError(source_name + ": not well-formed XML (line " + std::to_string(document.ErrorLineNum()) +
                      "): " + xmlErrorWords(document.ErrorName(), document.ErrorStr()) +
                      "; fix the XML before the transmissions can be read");
  }
  const tinyxml2::XMLElement* root = document.RootElement();
  if (root == nullptr || std::string_view(root->Name()) != "robot") {
    throw ConfigError(source_name +
                      ": the root element is not <robot>; a URDF robot description "
                      "starts with <robot name=\"...\">");
  }
  const urdf::ModelInterfaceSharedPtr robot = parseUrdfWithUrdfdom(urdf_xml, source_name, false);

  Problems problems(source_name);
  UsedNames used;
  ParseNotes notes;
  std::vector<TransmissionInfo> infos;
  std::vector<std::string> labels;  // how messages name each of infos
  std::vector<std::string> pr2_form;   // labels of transmissions in the pre-ros_control form
  std::vector<std::string> pr2_types;  // their type attributes, each once
  int index = 0;
  for (auto* element = root->FirstChildElement("transmission"); element != nullptr;
       element = element->NextSiblingElement("transmission")) {
    ++index;
    TransmissionInfo info;
    const char* name = element->Attribute("name");
    info.name = name != nullptr ? trim(name) : "";
    const std::string label =
        info.name.empty() ? "#" + std::to_string(index) : "'" + info.name + "'";
    problems.setTransmission(label);
    if (info.name.empty()) problems.add("has no name attribute; add name=\"<unique transmission name>\"");
    // A skipped transmission's name counts too; a placed one's is counted
    // when placed (a merged one's is not: franka's share their name).
    const auto count_name = [&] {
      if (!info.name.empty() && ++used.transmission_count[info.name] == 2) {
        problems.add("the name is used by more than one <transmission>; give each a unique name");
      }
    };

    if (isPr2MechanismForm(element)) {
      count_name();
      // The pre-ros_control form (pr2_mechanism_model: type="..." attribute, no
      // hardware interface anywhere). ros_control cannot use it either; the
      // simulation skips it and drives the joints as if it were not there.
      // One warning for all of them (a PR2 has 30).
      pr2_form.push_back(label);
      const std::string type = element->Attribute("type");
      if (std::find(pr2_types.begin(), pr2_types.end(), type) == pr2_types.end()) pr2_types.push_back(type);
      continue;
    }

    const std::string written_type = readType(element);
    const TypeRule* rule = findTypeRule(withTransmissionPrefix(written_type));
    info.type = rule != nullptr ? rule->type : written_type;
    if (written_type.empty()) {
      problems.add(
          "has no <type>; add e.g. "
          "<type>transmission_interface/SimpleTransmission</type>");
    } else if (rule == nullptr) {
      // As gazebo_ros_control: a type the simulation cannot model is skipped,
      // not fatal; its joints are driven as if it were not there.
      count_name();
      logger().warn(
          "{}: transmission {}: unknown type '{}'; the transmission is skipped (its joints are driven by their "
          "other transmissions, or get the implicit SimpleTransmission, reduction 1, when simulated). Use "
          "transmission_interface/SimpleTransmission, transmission_interface/DifferentialTransmission or "
          "transmission_interface/FourBarLinkageTransmission",
          source_name, label, written_type);
      continue;
    }

    readJoints(element, *robot, label, source_name, info, problems);
    readActuators(element, label, source_name, info, notes, problems);
    if (rule != nullptr) validateForType(info, *rule, problems);
    placeTransmission(std::move(info), label, infos, labels, used, notes, problems);
  }
  warnPr2MechanismForm(pr2_form, pr2_types, source_name);
  if (!problems.empty()) problems.raise();
  logNotes(notes, source_name);
  return infos;
}

std::unique_ptr<Transmission> makeTransmission(const TransmissionInfo& info) {
  const TypeRule* rule = findTypeRule(info.type);
  const std::string label = "transmission '" + info.name + "'";
  if (rule == nullptr) {
    throw ConfigError(label + ": unknown type '" + info.type +
                      "'; use transmission_interface/SimpleTransmission, "
                      "DifferentialTransmission or FourBarLinkageTransmission");
  }
  if (info.joints.size() != rule->num_joints || info.actuators.size() != rule->num_actuators) {
    throw ConfigError(
        label + ": " + rule->short_name + " needs " + std::to_string(rule->num_joints) +
        " joint(s) and " + std::to_string(rule->num_actuators) + " actuator(s), got " +
        std::to_string(info.joints.size()) + " and " + std::to_string(info.actuators.size()));
  }
  try {
    if (info.type == kSimpleTransmissionType) {
      return std::make_unique<SimpleTransmission>(info.actuators[0].mechanical_reduction,
                                                  info.joints[0].offset);
    }
    const std::array<double, 2> actuator_reductions = {info.actuators[0].mechanical_reduction,
                                                       info.actuators[1].mechanical_reduction};
    const std::array<double, 2> joint_reductions = {info.joints[0].mechanical_reduction,
                                                    info.joints[1].mechanical_reduction};
    const std::array<double, 2> joint_offsets = {info.joints[0].offset, info.joints[1].offset};
    if (info.type == kDifferentialTransmissionType) {
      return std::make_unique<DifferentialTransmission>(actuator_reductions, joint_reductions,
                                                        joint_offsets);
    }
    return std::make_unique<FourBarLinkageTransmission>(actuator_reductions, joint_reductions,
                                                        joint_offsets);
  } catch (const ConfigError& e) {
    throw ConfigError(label + ": " + e.what());
  }
}

}  // namespace servoloop::transmissions
