#include "servoloop/description/robot_model.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/text_file.hpp"
#include "servoloop/core/xml_error_text.hpp"
#include "servoloop/description/package_path.hpp"
#include "servoloop/description/simulatable_urdf.hpp"
#include "servoloop/description/xacro.hpp"

namespace servoloop {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& source_name, const std::string& what) {
  throw ConfigError(source_name + ": " + what);
}

// ---------------------------------------------------------------------------
// XML-level checks, made before urdfdom so the messages can name the element.

// The attributes urdfdom reads as numbers, by element. Other elements (a
// <verbose value="Yes"/> inside a link, extension tags) are not URDF's and are
// left alone, as urdfdom leaves them.
const std::set<std::string>* numericAttributes(const std::string& element) {
  static const std::map<std::string, std::set<std::string>> by_element{
      {"origin", {"xyz", "rpy"}},
      {"axis", {"xyz"}},
      {"limit", {"lower", "upper", "effort", "velocity"}},
      {"safety_controller", {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}},
      {"dynamics", {"damping", "friction"}},
      {"calibration", {"rising", "falling", "reference_position"}},
      {"mimic", {"multiplier", "offset"}},
      {"mass", {"value"}},
      {"inertia", {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}},
      {"box", {"size"}},
      {"cylinder", {"radius", "length"}},
      {"sphere", {"radius"}},
      {"capsule", {"radius", "length"}},
      {"mesh", {"scale"}}};
  const auto it = by_element.find(element);
  return it == by_element.end() ? nullptr : &it->second;
}

// "link 'link2' <inertial><origin>": the owning link/joint and the path below it.
std::string describeElement(const tinyxml2::XMLElement* element) {
  std::string path;
  const tinyxml2::XMLElement* e = element;
  while (e != nullptr) {
    const std::string tag = e->Name();
    const tinyxml2::XMLElement* parent = e->Parent() ? e->Parent()->ToElement() : nullptr;
    const bool top_level = parent != nullptr && std::string(parent->Name()) == "robot";
    if (top_level) {
      const char* name = e->Attribute("name");
      return tag + " '" + (name ? name : "?") + "'" + (path.empty() ? "" : " " + path);
    }
    path = "<" + tag + ">" + path;
    e = parent;
  }
  return path;
}

// The largest magnitudes a URDF may give, far beyond any real robot: past
// them the physics is meaningless. The engines compute in floating point (a
// double carries about 16 significant digits, Bullet's and MuJoCo's contact
// and constraint code is tuned for metres and kilograms near 1): a mass of
// 1e308 kg overflows the first product it enters (NaN or infinity in the
// joints a few steps later), and at 1e9 m from the origin a double cannot
// resolve positions finer than about 1e-7 m, so a link there cannot move by
// a control step's worth. docs/reliability.md lists them.
constexpr double kMaxLength_m = 1e9;            // origin xyz and geometry sizes
constexpr double kMaxMass_kg = 1e12;            // <mass value>
constexpr double kMaxInertia_kgm2 = 1e15;       // each <inertia> component (kMaxMass_kg × (~30 m)²)

// An upper bound on an attribute's magnitude (see above), with its unit.
struct MagnitudeBound {
  double at_most;
  const char* unit;
};

// How many numbers an attribute holds (1 unless listed), the least value
// that means something physical (none unless listed) and the largest
// magnitude the engines can simulate (none unless listed).
struct NumberRule {
  std::size_t count = 1;
  std::optional<double> at_least;
  bool positive = false;  // > 0 rather than >= at_least
  const char* meaning = "";
  std::optional<MagnitudeBound> at_most = std::nullopt;
};

NumberRule numberRule(const std::string& element, const std::string& attribute) {
  const MagnitudeBound length{kMaxLength_m, "m"};
  if (element == "origin" && attribute == "xyz") return {3, std::nullopt, false, "x y z", length};
  if (element == "axis" && attribute == "xyz") return {3, std::nullopt, false, "x y z"};
  if (element == "origin" && attribute == "rpy") return {3, std::nullopt, false, "roll pitch yaw"};
  if (element == "mesh" && attribute == "scale") return {3, std::nullopt, false, "x y z factors"};
  if (element == "box" && attribute == "size") return {3, std::nullopt, true, "three sizes > 0 (m)", length};
  if (element == "cylinder" || element == "sphere" || element == "capsule") {
    return {1, std::nullopt, true, "a size > 0 (m)", length};
  }
  if (element == "mass" && attribute == "value") {
    return {1, std::nullopt, false, "a mass (kg)", MagnitudeBound{kMaxMass_kg, "kg"}};
  }
  if (element == "inertia") {
    return {1, std::nullopt, false, "an inertia (kg·m²)", MagnitudeBound{kMaxInertia_kgm2, "kg·m²"}};
  }
  if (element == "limit" && (attribute == "effort" || attribute == "velocity")) {
    return {1, 0.0, false, "a limit >= 0 (a magnitude; URDF has no negative limits)"};
  }
  if (element == "safety_controller" && (attribute == "k_position" || attribute == "k_velocity")) {
    return {1, 0.0, false, "a gain >= 0 (ros_control's soft limits: a negative gain drives the joint past its limit)"};
  }
  if (element == "dynamics") return {1, 0.0, false, "a coefficient >= 0 (a negative one would add energy)"};
  return {};
}

// Every numeric attribute under <link> and <joint> must hold finite numbers,
// as many as it needs, in the range that means something physical.
void checkNumbers(const tinyxml2::XMLElement* element, const std::string& source_name) {
  const std::set<std::string>* numeric = numericAttributes(element->Name());
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); numeric != nullptr && a != nullptr;
       a = a->Next()) {
    if (numeric->count(a->Name()) == 0) continue;
    const NumberRule rule = numberRule(element->Name(), a->Name());
    const auto wrong = [&](const std::string& why) {
      fail(source_name, describeElement(element) + " attribute " + a->Name() + "=\"" + a->Value() + "\": " + why);
    };
    std::istringstream tokens(a->Value());
    std::string token;
    std::size_t count = 0;
    bool zero_vector = true;
    while (tokens >> token) {
      ++count;
      errno = 0;
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      const bool parsed = end != nullptr && *end == '\0' && end != token.c_str();
      if (!parsed || !std::isfinite(value)) wrong("'" + token + "' is not a finite number; write a finite decimal value");
      zero_vector = zero_vector && value == 0.0;
      if ((rule.positive && !(value > 0.0)) || (rule.at_least && value < *rule.at_least)) {
        wrong("'" + token + "' is out of range; expected " + rule.meaning);
      }
      if (rule.at_most && std::fabs(value) > rule.at_most->at_most) {
        std::ostringstream bound;
        bound << rule.at_most->at_most;
        wrong("'" + token + "' is beyond " + bound.str() + " " + rule.at_most->unit +
              ", the largest magnitude servoloop simulates: the physics engines compute in floating point, and "
              "values this large overflow or lose all precision (NaN joints); no real robot comes near it");
      }
    }
    // (A fixed or floating joint has no axis to speak of: exporters often write 0 0 0 there.)
    const tinyxml2::XMLElement* owner = element->Parent() ? element->Parent()->ToElement() : nullptr;
    const char* joint_type = owner != nullptr ? owner->Attribute("type") : nullptr;
    const bool moves_about_axis = joint_type != nullptr && (std::string(joint_type) == "revolute" ||
                                                            std::string(joint_type) == "continuous" ||
                                                            std::string(joint_type) == "prismatic");
    if (std::string(element->Name()) == "axis" && count == 3 && zero_vector && moves_about_axis) {
      wrong("a zero vector has no direction; give the joint's axis, e.g. xyz=\"0 0 1\"");
    }
    if (count != rule.count) {
      wrong(std::to_string(count) + " number" + (count == 1 ? "" : "s") + " where " + std::to_string(rule.count) +
            (rule.count == 1 ? " is" : " are") + " expected" + (rule.count == 3 ? std::string(" (") + rule.meaning + ")" : ""));
    }
  }
  if (std::string(element->Name()) == "limit" && element->Attribute("lower") != nullptr &&
      element->Attribute("upper") != nullptr && element->DoubleAttribute("lower") > element->DoubleAttribute("upper")) {
    fail(source_name, describeElement(element) + ": lower=\"" + element->Attribute("lower") + "\" is above upper=\"" +
                          element->Attribute("upper") + "\"; swap them (ros_control refuses such limits)");
  }
  for (const tinyxml2::XMLElement* c = element->FirstChildElement(); c != nullptr;
       c = c->NextSiblingElement()) {
    checkNumbers(c, source_name);
  }
}

std::string joinQuoted(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

// Tree structure: links exist, joints have known types and name known links,
// every link has at most one parent, exactly one root, no cycle.
void checkStructure(const tinyxml2::XMLElement* robot, const std::string& source_name) {
  static const std::set<std::string> known_types{"revolute", "continuous", "prismatic",
                                                 "fixed",    "floating",   "planar"};
  std::vector<std::string> links;
  std::set<std::string> link_set;
  for (auto* l = robot->FirstChildElement("link"); l != nullptr; l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    if (name == nullptr) fail(source_name, "a <link> has no name attribute; give every link a unique name");
    if (!link_set.insert(name).second) {
      fail(source_name, std::string("link '") + name + "' is defined twice; link names must be unique");
    }
    links.emplace_back(name);
  }
  if (links.empty()) fail(source_name, "no <link> elements; a URDF needs at least one link");

  std::map<std::string, std::string> parent_joint_of;  // child link -> joint
  std::multimap<std::string, std::string> children_of;  // parent link -> child link
  for (auto* j = robot->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
    const char* name_attr = j->Attribute("name");
    const std::string name = name_attr ? name_attr : "?";
    if (name_attr == nullptr) fail(source_name, "a <joint> has no name attribute; give every joint a unique name");
    const char* type = j->Attribute("type");
    if (type == nullptr || known_types.count(type) == 0) {
      fail(source_name, "joint '" + name + "' has " +
                            (type ? "unknown type '" + std::string(type) + "'" : std::string("no type")) +
                            "; use one of revolute, continuous, prismatic, fixed, floating, planar");
    }
    const auto* parent = j->FirstChildElement("parent");
    const auto* child = j->FirstChildElement("child");
    const char* parent_link = parent ? parent->Attribute("link") : nullptr;
    const char* child_link = child ? child->Attribute("link") : nullptr;
    if (parent_link == nullptr || child_link == nullptr) {
      fail(source_name, "joint '" + name + "' needs <parent link=\"...\"/> and <child link=\"...\"/>");
    }
    for (const char* l : {parent_link, child_link}) {
      if (link_set.count(l) == 0) {
        fail(source_name, "joint '" + name + "' refers to link '" + l + "', which is not defined; add the <link> or fix the name");
      }
    }
    auto [it, inserted] = parent_joint_of.emplace(child_link, name);
    if (!inserted) {
      fail(source_name, std::string("link '") + child_link + "' is the child of two joints, '" + it->second +
                            "' and '" + name + "' (a kinematic cycle); a URDF must be a tree: remove one joint");
    }
    children_of.emplace(parent_link, child_link);
  }
  // A mimic joint follows a joint of this robot.
  std::set<std::string> joint_names;
  for (auto* j = robot->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
    joint_names.insert(j->Attribute("name"));
  }
  for (auto* j = robot->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
    const auto* mimic = j->FirstChildElement("mimic");
    if (mimic == nullptr) continue;
    const char* followed = mimic->Attribute("joint");
    const std::string name = j->Attribute("name");
    if (followed == nullptr) fail(source_name, "joint '" + name + "' <mimic> needs joint=\"...\": the joint it follows");
    if (joint_names.count(followed) == 0 || name == followed) {
      fail(source_name, "joint '" + name + "' <mimic joint=\"" + followed + "\">: " +
                            (name == followed ? std::string("a joint cannot follow itself")
                                              : "no joint '" + std::string(followed) + "' in this robot") +
                            "; name the joint it follows");
    }
  }

  std::vector<std::string> roots;
  for (const auto& l : links) {
    if (parent_joint_of.count(l) == 0) roots.push_back(l);
  }
  if (roots.empty()) {
    fail(source_name, "every link has a parent joint, so the joints form a kinematic cycle and there is no root link; "
                      "remove a joint to break the cycle");
  }
  if (roots.size() > 1) {
    fail(source_name, "several root links (" + joinQuoted(roots) +
                          "); connect them with joints so exactly one root remains");
  }
  std::set<std::string> reached{roots.front()};
  std::vector<std::string> stack{roots.front()};
  while (!stack.empty()) {
    const std::string l = stack.back();
    stack.pop_back();
    auto range = children_of.equal_range(l);
    for (auto it = range.first; it != range.second; ++it) {
      if (reached.insert(it->second).second) stack.push_back(it->second);
    }
  }
  std::vector<std::string> in_cycle;
  for (const auto& l : links) {
    if (reached.count(l) == 0) in_cycle.push_back(l);
  }
  if (!in_cycle.empty()) {
    fail(source_name, "links " + joinQuoted(in_cycle) + " are not reachable from root link '" + roots.front() +
                          "': their joints form a kinematic cycle; remove a joint to break it");
  }
}

void checkXml(const std::string& xml, const std::string& source_name) {
  if (const auto offset = invalidUtf8Offset(xml)) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(xml[*offset]));
    fail(source_name, "byte " + std::to_string(*offset) + " (" + hex +
                          ") is not UTF-8, the encoding URDF is read in; save the file as UTF-8");
  }
  if (xml.find("<!ENTITY") != std::string::npos) {
    fail(source_name, "declares XML entities (<!DOCTYPE ... <!ENTITY ...>), which urdfdom and ROS's URDF parser "
                      "do not expand; write the values out (or use xacro properties)");
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    fail(source_name, "not valid XML (line " + std::to_string(doc.ErrorLineNum()) +
                          "): " + xmlErrorWords(doc.ErrorName(), doc.ErrorStr()) + "; fix the XML syntax");
  }
  // Text outside the root element (tinyxml2 lets it through; urdfdom then
  // reports an "empty document").
  for (const tinyxml2::XMLNode* n = doc.FirstChild(); n != nullptr; n = n->NextSibling()) {
    if (const tinyxml2::XMLText* text = n->ToText()) {
      std::string words = text->Value() ? text->Value() : "";
      if (words.size() > 40) words = words.substr(0, 40) + "...";
      fail(source_name, "not valid XML (line " + std::to_string(text->GetLineNum()) + "): text '" + words +
                            "' outside the root element; is this a URDF file?");
    }
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Name()) != "robot") {
    fail(source_name, std::string("the root element is <") + (robot ? robot->Name() : "") +
                          ">, expected <robot>; is this a URDF file?");
  }
  for (auto* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link" || tag == "joint") checkNumbers(e, source_name);
  }
  checkStructure(robot, source_name);
}

// ---------------------------------------------------------------------------
// urdfdom parsing with its console_bridge output captured.

// urdfdom's links own their children (Link::child_links holds shared
// pointers), so a model dies link by link down the tree: freeing the root
// frees its child from inside the root's destructor, and so on, one nesting
// of destructor calls per link: with urdfdom 3.0, a serial chain of 20,000
// links overflows a 1 MB stack that way, one of 200,000 links an 8 MB one.
// Every model servoloop hands out is owned through this holder, which first
// cuts the links from their children, so that the model's map then frees
// them one after another. (A link kept beyond its model has no children.)
struct FlatTeardownModel {
  FlatTeardownModel() = default;
  FlatTeardownModel(const FlatTeardownModel&) = delete;  // a copy's teardown would cut the model it shares
  FlatTeardownModel& operator=(const FlatTeardownModel&) = delete;
  urdf::ModelInterfaceSharedPtr model;
  ~FlatTeardownModel() {
    if (!model) return;
    for (auto& [name, link] : model->links_) {
      if (link) link->child_links.clear();
    }
  }
};

class CapturingOutputHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      errors += (errors.empty() ? "" : "; ") + text;
    } else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      warnings.push_back(text);
    }
  }
  std::string errors;
  std::vector<std::string> warnings;
};

}  // namespace

urdf::ModelInterfaceSharedPtr parseUrdfWithUrdfdom(const std::string& xml, const std::string& source_name,
                                                   bool report_warnings) {
  // console_bridge's handler is process-global; serialise the swap.
  static std::mutex handler_mutex;
  CapturingOutputHandler handler;
  urdf::ModelInterfaceSharedPtr model;
  {
    std::lock_guard<std::mutex> lock(handler_mutex);
    console_bridge::useOutputHandler(&handler);
    try {
      model = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      handler.errors += (handler.errors.empty() ? "" : "; ") + std::string(e.what());
    }
    console_bridge::restorePreviousOutputHandler();
  }
  if (!model) {
    fail(source_name, "urdfdom could not parse the URDF: " +
                          (handler.errors.empty() ? std::string("no reason given") : handler.errors));
  }
  // Owned by the holder from here on, so that a throw below (or any later
  // owner) frees the model without recursion.
  const auto holder = std::make_shared<FlatTeardownModel>();
  holder->model = std::move(model);
  model = urdf::ModelInterfaceSharedPtr(holder, holder->model.get());
  if (report_warnings) {
    // An <inertial> urdfdom cannot read (a mass written "  1.0  ") leaves
    // its link with a zero mass; refused here, naming the value, rather than
    // as a zero mass the user never wrote.
    // (A string search, not std::regex: compiling one costs milliseconds of
    // every start-up.)
    constexpr std::string_view kUnreadableInertial = "Could not parse inertial element for Link [";
    if (const std::size_t found = handler.errors.find(kUnreadableInertial); found != std::string::npos) {
      const std::size_t name_start = found + kUnreadableInertial.size();
      const std::size_t name_end = handler.errors.find(']', name_start);
      if (name_end != std::string::npos) {
        fail(source_name, "link '" + handler.errors.substr(name_start, name_end - name_start) +
                              "': urdfdom could not read its <inertial> (" + handler.errors +
                              "); write each value as a plain number, e.g. <mass value=\"1.0\"/>, without spaces, "
                              "units or expressions");
      }
    }
    for (const auto& w : handler.warnings) logger().warn("{}: urdfdom: {}", source_name, w);
    // Errors urdfdom recovers from (a <collision> it cannot read): ROS goes
    // on without the element, and so does servoloop, saying so.
    if (!handler.errors.empty()) {
      logger().warn("{}: urdfdom: {}; the element is left out, as ROS does: fix it to keep it", source_name,
                    handler.errors);
    }
  }
  return model;
}

namespace {

// ---------------------------------------------------------------------------
// Model-level checks.

// Relative slack of the principal-moment triangle inequality (of the largest moment).
constexpr double kInertiaTriangleTolerance = 1e-9;

bool attachedByFixedJoint(const urdf::LinkSharedPtr& child) {
  return child && child->parent_joint && child->parent_joint->type == urdf::Joint::FIXED;
}

// For every link, the mass of the links attached below it through fixed
// joints, which a simulator lumps into one rigid body with it (as Gazebo
// does): Σ over its fixed children, in order, of (child's mass + the child's
// own such mass). Computed once for the whole tree, children before parents,
// with an explicit stack: a recursion per link would overflow the call stack
// on a chain of thousands of links, and summing each link's subtree anew
// would take time quadratic in the chain's length.
std::unordered_map<const urdf::Link*, double> fixedChildrenMasses(const urdf::ModelInterface& model) {
  std::unordered_map<const urdf::Link*, double> masses;
  // A link with whether its fixed children are on the stack above it already.
  std::vector<std::pair<const urdf::Link*, bool>> stack;
  for (const auto& [name, start] : model.links_) {
    if (!start || masses.count(start.get()) != 0) continue;
    stack.emplace_back(start.get(), false);
    while (!stack.empty()) {
      const auto [link, children_pushed] = stack.back();
      if (!children_pushed) {
        stack.back().second = true;
        for (const auto& child : link->child_links) {
          if (attachedByFixedJoint(child) && masses.count(child.get()) == 0) stack.emplace_back(child.get(), false);
        }
        continue;
      }
      stack.pop_back();
      double mass = 0.0;
      for (const auto& child : link->child_links) {
        if (!attachedByFixedJoint(child)) continue;
        mass += (child->inertial ? child->inertial->mass : 0.0) + masses.at(child.get());
      }
      masses[link] = mass;
    }
  }
  return masses;
}

// `fixed_children_mass`: the link's entry of fixedChildrenMasses.
void checkInertial(const urdf::Link& link, double fixed_children_mass, const std::string& source_name) {
  const urdf::JointConstSharedPtr& joint = link.parent_joint;
  const bool moving = joint && joint->type != urdf::Joint::FIXED;
  const std::string moved_by = moving ? " (moved by joint '" + joint->name + "')" : "";
  const std::string where = "link '" + link.name + "'" + moved_by;
  // A massless link carrying massive links on fixed joints is one rigid body
  // with their mass.
  const bool lumped_mass = fixed_children_mass > 0.0;
  if (!link.inertial) {
    if (moving && !lumped_mass) {
      fail(source_name, where +
                            " has no <inertial>; add <inertial> with <mass> > 0 and <inertia> (loadRobotModelFile "
                            "and the simulators leave such a link out with a warning, as Gazebo does)");
    }
    return;
  }
  const urdf::Inertial& in = *link.inertial;
  if (in.mass < 0.0) {
    fail(source_name, where + " <inertial><mass value=\"" + std::to_string(in.mass) +
                          "\"> is negative; a mass must be > 0");
  }
  if (!moving) return;
  if (in.mass == 0.0) {
    if (lumped_mass) return;
    fail(source_name, where + " <inertial><mass> is zero; a moving link needs a mass > 0");
  }
  Eigen::Matrix3d inertia;
  inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  if (!(moments.minCoeff() > 0.0)) {
    std::ostringstream m;
    m << where << " <inertial><inertia> is not positive definite (principal moments " << moments(0) << ", "
      << moments(1) << ", " << moments(2) << "); give ixx, iyy, izz > 0 and small enough products of inertia";
    fail(source_name, m.str());
  }
  // Triangle inequality: with I_x = ∫(y² + z²) dm etc. about the principal
  // axes, I_x + I_y − I_z = 2∫z² dm ≥ 0, so the largest moment is at most the
  // sum of the other two, equal for a flat body (a thin disc or plate); a thin
  // rod (ε, I, I) passes too. MuJoCo refuses a body that breaks it. The
  // relative tolerance accepts flat bodies whose moments were rounded.
  const double largest = moments(2);  // eigenvalues() is in increasing order
  if (largest > moments(0) + moments(1) + kInertiaTriangleTolerance * largest) {
    std::ostringstream m;
    m << where << " <inertial><inertia> breaks the triangle inequality (principal moments " << moments(0) << ", "
      << moments(1) << ", " << largest << ": the largest is more than the sum of the other two, "
      << moments(0) + moments(1)
      << "); no rigid body has such moments; correct ixx, iyy, izz so that each principal moment is at most "
         "the sum of the other two (e.g. a solid box of mass m and sides a, b, c: ixx = m(b² + c²)/12, "
         "iyy = m(a² + c²)/12, izz = m(a² + b²)/12)";
    fail(source_name, m.str());
  }
}

// A missing visual mesh is reported once per process, although the node and
// the simulated hardware each parse the description.
void warnMissingVisualMeshOnce(const std::string& text) {
  static std::mutex mutex;
  static std::set<std::string> reported;
  std::lock_guard lock(mutex);
  if (reported.insert(text).second) logger().warn("{}", text);
}

// Returns the absolute path of an existing mesh file. A missing one throws
// naming the link when `required` (collision: every backend needs it);
// otherwise (visual: no backend draws it) it is one warning and the URI stays.
std::string resolveMesh(const std::string& uri, const fs::path& base_dir, const std::string& what,
                        const std::string& source_name, bool required) {
  std::vector<fs::path> candidates;
  const std::string file_prefix = "file://";
  if (uri.rfind("package://", 0) == 0) {
    try {
      candidates.push_back(resolvePackageUri(uri, base_dir, source_name));
    } catch (const ConfigError& e) {
      if (required) fail(source_name, what + " mesh '" + uri + "': " + e.what());
      warnMissingVisualMeshOnce(fmt::format("{}: {} mesh '{}': {}; no backend draws visual meshes, so the robot "
                                            "loads without it",
                                            source_name, what, uri, e.what()));
      return uri;
    }
  } else {
    fs::path path = uri.rfind(file_prefix, 0) == 0 ? fs::path(uri.substr(file_prefix.size())) : fs::path(uri);
    candidates.push_back(path.is_absolute() ? path : base_dir / path);
  }
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return fs::absolute(c).lexically_normal().string();
  }
  std::string tried;
  for (std::size_t i = 0; i < candidates.size() && i < 4; ++i) {
    tried += (tried.empty() ? "" : ", ") + candidates[i].lexically_normal().string();
  }
  if (candidates.size() > 4) tried += ", ...";
  if (!required) {
    warnMissingVisualMeshOnce(fmt::format("{}: {} mesh '{}' not found (looked for {}); no backend draws visual "
                                          "meshes, so the robot loads without it",
                                          source_name, what, uri, tried));
    return uri;
  }
  fail(source_name, what + " mesh '" + uri + "' not found (looked for " + tried +
                        "); fix the filename or add the file");
}

void resolveMeshes(urdf::Link& link, const fs::path& base_dir, const std::string& source_name) {
  auto resolve = [&](const urdf::GeometrySharedPtr& geometry, const std::string& element, bool required) {
    if (!geometry || geometry->type != urdf::Geometry::MESH) return;
    auto* mesh = static_cast<urdf::Mesh*>(geometry.get());
    mesh->filename =
        resolveMesh(mesh->filename, base_dir, "link '" + link.name + "' " + element, source_name, required);
  };
  for (const auto& c : link.collision_array) {
    if (c) resolve(c->geometry, "<collision>", true);
  }
  for (const auto& v : link.visual_array) {
    if (v) resolve(v->geometry, "<visual>", false);
  }
  // urdfdom also keeps the first element as link.collision/link.visual; they
  // share the geometry objects with the arrays, so they are resolved already.
}

}  // namespace

const char* jointTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

std::shared_ptr<const urdf::ModelInterface> parseRobotModel(const std::string& xml,
                                                            const std::string& source_name) {
  checkXml(xml, source_name);
  urdf::ModelInterfaceSharedPtr model = parseUrdfWithUrdfdom(xml, source_name, true);
  const fs::path base_dir = fs::path(source_name).has_parent_path() ? fs::path(source_name).parent_path()
                                                                     : fs::current_path();
  const auto fixed_children_masses = fixedChildrenMasses(*model);
  for (auto& [name, link] : model->links_) {
    checkInertial(*link, fixed_children_masses.at(link.get()), source_name);
    resolveMeshes(*link, base_dir, source_name);
  }
  return model;
}

std::shared_ptr<const urdf::ModelInterface> loadRobotModelFile(const std::string& path, const XacroArgs& args) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw ConfigError(path + ": URDF file not found; check the path (relative paths start at " +
                      fs::current_path().string() + ")");
  }
  if (fs::is_directory(path, ec)) throw ConfigError(path + ": is a folder, not a URDF file");
  return parseRobotModel(simulatableUrdf(readRobotDescription(path, args), path).xml, path);
}

}  // namespace servoloop
