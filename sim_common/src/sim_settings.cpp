#include "servoloop/sim_common/sim_settings.hpp"

#include <cmath>
#include <string_view>
#include <vector>

#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/time.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/params/parameters_yaml.hpp"
#include "servoloop/params/schema.hpp"

namespace servoloop::sim_common {
namespace {

std::string keyPath(const std::string& ns, std::string_view key) {
  std::string path = ns;
  if (!path.empty() && path.back() != '/') path += '/';
  path += key;
  return path;
}

std::string describe(const YAML::Node& value) {
  if (value.IsScalar()) return "'" + value.Scalar() + "'";
  if (value.IsSequence()) return "a list";
  if (value.IsMap()) return "a map";
  return "nothing";
}

double readNumber(const YAML::Node& value, const std::string& path) {
  const auto fail = [&]() { return ConfigError(path + ": expected a number, got " + describe(value)); };
  if (!value.IsScalar()) throw fail();
  double number = 0.0;
  try {
    number = value.as<double>();
  } catch (const YAML::BadConversion&) {
    throw fail();
  }
  if (!std::isfinite(number)) throw ConfigError(path + ": expected a finite number, got " + describe(value));
  return number;
}

bool readBool(const YAML::Node& value, const std::string& path) {
  const auto fail = [&]() {
    return ConfigError(path + ": expected a boolean (true or false), got " + describe(value));
  };
  if (!value.IsScalar()) throw fail();
  try {
    return value.as<bool>();
  } catch (const YAML::BadConversion&) {
    throw fail();
  }
}

void requireMap(const YAML::Node& node, const std::string& path, const char* what) {
  if (!node.IsMap()) throw ConfigError(path + ": expected a map of " + what + ", got " + describe(node));
}

// The keys of a robot's `sim:` map and of each entry of its `actuators:` map.
const params::Schema& simSettingsSchema() {
  using params::ValueType;
  static const params::Schema schema(
      "simulation settings",
      {
          {"time_step", ValueType::number, "the physics step (s)", {.min = kMinTimeStepS, .max = kMaxTimeStepS}},
          {"gravity", ValueType::number_list, "gravity [x, y, z] (m/s²)"},
          {"ground_plane", ValueType::boolean, "a ground plane at z = 0"},
          {"initial_positions", ValueType::map, "joint positions at the start (rad or m)"},
          {"fixed_base", ValueType::boolean, "the root link is fixed to the world"},
          {"pose", ValueType::number_list, "the root link's pose [x, y, z(, roll, pitch, yaw)] (m, rad)"},
          {"self_collide", ValueType::boolean, "links of the robot collide with each other"},
      },
      params::UnknownKeys::warn);
  return schema;
}

const params::Schema& actuatorSchema() {
  using params::ValueType;
  static const params::Schema schema(
      "actuator parameters",
      {
          {"max_effort", ValueType::number, "the motor's effort limit (N·m or N)", {.min = 0.0, .min_exclusive = true}},
          {"rotor_inertia", ValueType::number, "the rotor's inertia seen at the joint (kg·m²)", {.min = 0.0}},
      },
      params::UnknownKeys::warn);
  return schema;
}

bool isMovable(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC;
}

std::string movableJointNames(const urdf::ModelInterface& model) {
  std::string names;
  for (const auto& [name, joint] : model.joints_) {
    if (joint && isMovable(*joint)) names += (names.empty() ? "" : ", ") + name;
  }
  return names.empty() ? "none" : names;
}

void readInitialPositions(const YAML::Node& node, const std::string& path,
                          const urdf::ModelInterface& model, SimSettings& settings) {
  requireMap(node, path, "joint names to positions");
  for (const auto& entry : node) {
    const std::string joint_name = entry.first.as<std::string>();
    const std::string joint_path = keyPath(path, joint_name);
    const auto joint_it = model.joints_.find(joint_name);
    if (joint_it == model.joints_.end() || !joint_it->second || !isMovable(*joint_it->second)) {
      throw ConfigError(joint_path + ": robot '" + model.getName() + "' has no movable joint '" +
                        joint_name + "' (movable joints: " + movableJointNames(model) + ")");
    }
    const double position = readNumber(entry.second, joint_path);
    const urdf::Joint& joint = *joint_it->second;
    if (joint.type != urdf::Joint::CONTINUOUS && joint.limits &&
        joint.limits->lower < joint.limits->upper &&
        (position < joint.limits->lower || position > joint.limits->upper)) {
      throw ConfigError(joint_path + ": " + std::to_string(position) +
                        " lies outside the joint's URDF position limits [" +
                        std::to_string(joint.limits->lower) + ", " +
                        std::to_string(joint.limits->upper) + "]; choose a position inside them");
    }
    settings.initial_positions[joint_name] = position;
  }
}

}  // namespace

bool urdfRequestsSelfCollision(const std::string& urdf_xml) {
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) return false;
  const tinyxml2::XMLElement* robot = document.RootElement();
  if (robot == nullptr) return false;
  bool requested = false;
  for (auto* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    if (gazebo->Attribute("reference") != nullptr) continue;  // a link's settings, not the model's
    const tinyxml2::XMLElement* flag = gazebo->FirstChildElement("self_collide");
    if (flag == nullptr || flag->GetText() == nullptr) continue;
    const std::string text = flag->GetText();
    requested = text.find("true") != std::string::npos || text.find('1') != std::string::npos;
  }
  return requested;
}

bool isFixedBase(const urdf::ModelInterface& model, BaseMode mode) {
  switch (mode) {
    case BaseMode::fixed: return true;
    case BaseMode::floating: return false;
    case BaseMode::automatic: break;
  }
  const urdf::LinkConstSharedPtr root = model.getRoot();
  if (!root) return false;
  if (root->name == "world") return true;
  return !(rigidBodyMass(*root) > 0.0);
}

// The link's own mass plus, in child order, the rigid-body mass of each link
// fixed to it. Each link's partial sum waits on a stack of its own (not the
// call stack, which a chain of thousands of fixed links would overflow)
// while its fixed children are summed: the additions of the recursive
// definition, in the same order, so the same sum to the last bit.
double rigidBodyMass(const urdf::Link& link) {
  struct Partial {
    const urdf::Link* link;
    std::size_t next_child;
    double mass;
  };
  const auto own_mass = [](const urdf::Link& l) { return l.inertial ? l.inertial->mass : 0.0; };
  std::vector<Partial> stack{Partial{&link, 0, own_mass(link)}};
  while (true) {
    Partial& top = stack.back();
    const std::vector<urdf::LinkSharedPtr>& children = top.link->child_links;
    while (top.next_child < children.size()) {
      const urdf::LinkSharedPtr& child = children[top.next_child];
      if (child && child->parent_joint && child->parent_joint->type == urdf::Joint::FIXED) break;
      ++top.next_child;
    }
    if (top.next_child < children.size()) {
      const urdf::Link& child = *children[top.next_child++];
      stack.push_back(Partial{&child, 0, own_mass(child)});  // (`top` may move: not used after)
      continue;
    }
    const double mass = top.mass;
    stack.pop_back();
    if (stack.empty()) return mass;
    stack.back().mass += mass;
  }
}

SimSettings parseSimSettings(const YAML::Node& robot_ns, const urdf::ModelInterface& model,
                             const std::string& ns, bool urdf_self_collide) {
  SimSettings settings;
  settings.self_collide = urdf_self_collide;
  if (!robot_ns || !robot_ns.IsMap()) return settings;
  const YAML::Node sim = robot_ns["sim"];
  if (!sim.IsDefined() || sim.IsNull()) return settings;
  const std::string sim_path = keyPath(ns, "sim");
  requireMap(sim, sim_path,
             "simulation settings (time_step, gravity, ground_plane, initial_positions, fixed_base, pose, "
             "self_collide)");

  // Unknown keys (one warning each), types and the time step's range.
  const params::Parameters sim_params = params::parametersFromYaml(sim, sim_path);
  simSettingsSchema().check(sim_params);

  if (sim_params.has("time_step")) settings.time_step_s = simSettingsSchema().number(sim_params, "time_step");
  if (const YAML::Node value = sim["gravity"]; value.IsDefined()) {
    const std::string path = keyPath(sim_path, "gravity");
    if (!value.IsSequence() || value.size() != 3) {
      throw ConfigError(path + ": expected a list of 3 numbers [x, y, z] in m/s², got " +
                        describe(value));
    }
    for (int axis = 0; axis < 3; ++axis) {
      settings.gravity[axis] = readNumber(value[axis], path + "[" + std::to_string(axis) + "]");
    }
  }
  if (const YAML::Node value = sim["ground_plane"]; value.IsDefined()) {
    settings.ground_plane = readBool(value, keyPath(sim_path, "ground_plane"));
  }
  if (const YAML::Node value = sim["initial_positions"]; value.IsDefined() && !value.IsNull()) {
    readInitialPositions(value, keyPath(sim_path, "initial_positions"), model, settings);
  }
  if (const YAML::Node value = sim["fixed_base"]; value.IsDefined() && !value.IsNull()) {
    settings.base = readBool(value, keyPath(sim_path, "fixed_base")) ? BaseMode::fixed : BaseMode::floating;
  }
  if (const YAML::Node value = sim["pose"]; value.IsDefined() && !value.IsNull()) {
    const std::string path = keyPath(sim_path, "pose");
    if (!value.IsSequence() || (value.size() != 3 && value.size() != 6)) {
      throw ConfigError(path + ": expected [x, y, z] or [x, y, z, roll, pitch, yaw] (m, rad), got " +
                        describe(value));
    }
    double p[6] = {0, 0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < value.size(); ++i) p[i] = readNumber(value[i], path + "[" + std::to_string(i) + "]");
    settings.base_position = Eigen::Vector3d(p[0], p[1], p[2]);
    // URDF's rpy: roll about X, then pitch about Y, then yaw about Z, all fixed axes.
    settings.base_orientation = Eigen::AngleAxisd(p[5], Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(p[4], Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(p[3], Eigen::Vector3d::UnitX());
  }
  if (const YAML::Node value = sim["self_collide"]; value.IsDefined() && !value.IsNull()) {
    settings.self_collide = readBool(value, keyPath(sim_path, "self_collide"));
  }
  return settings;
}

std::map<std::string, ActuatorParameters> parseActuatorParameters(
    const YAML::Node& robot_ns, const std::vector<std::string>& actuator_names,
    const std::string& ns) {
  std::map<std::string, ActuatorParameters> parameters;
  for (const std::string& name : actuator_names) parameters[name] = ActuatorParameters{};
  if (!robot_ns || !robot_ns.IsMap()) return parameters;
  const YAML::Node actuators = robot_ns["actuators"];
  if (!actuators.IsDefined() || actuators.IsNull()) return parameters;
  const std::string actuators_path = keyPath(ns, "actuators");
  requireMap(actuators, actuators_path, "actuator names to parameters");

  for (const auto& entry : actuators) {
    const std::string name = entry.first.as<std::string>();
    const std::string path = keyPath(actuators_path, name);
    const auto it = parameters.find(name);
    if (it == parameters.end()) {
      std::string known;
      for (const std::string& n : actuator_names) known += (known.empty() ? "" : ", ") + n;
      throw ConfigError(path + ": the robot has no actuator '" + name + "' (actuators: " +
                        (known.empty() ? "none" : known) +
                        "; a joint without a <transmission> has the actuator '<joint>_motor')");
    }
    const YAML::Node node = entry.second;
    requireMap(node, path, "actuator parameters (max_effort, rotor_inertia)");
    const params::Parameters actuator = params::parametersFromYaml(node, path);
    actuatorSchema().check(actuator);
    if (actuator.has("max_effort")) it->second.max_effort = actuatorSchema().number(actuator, "max_effort");
    if (actuator.has("rotor_inertia")) it->second.rotor_inertia = actuatorSchema().number(actuator, "rotor_inertia");
  }
  return parameters;
}

}  // namespace servoloop::sim_common
