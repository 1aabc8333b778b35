#include "servoloop/description/simulatable_urdf.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <string_view>
#include <vector>

#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop {
namespace {

struct JointEdge {
  std::string name;
  std::string parent;
  std::string child;
  bool fixed = false;
};

// <inertial><mass value=...> of a link; 0 without one. A mass that is not a
// finite number >= 0 is an error here, before a negative or NaN mass could be
// taken for "no mass" and the link silently left out.
double linkMass(const tinyxml2::XMLElement* link, const std::string& source_name) {
  const tinyxml2::XMLElement* inertial = link->FirstChildElement("inertial");
  const tinyxml2::XMLElement* mass = inertial ? inertial->FirstChildElement("mass") : nullptr;
  const char* value = mass ? mass->Attribute("value") : nullptr;
  if (value == nullptr) return 0.0;
  std::string_view text(value);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  double number = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(number) || number < 0.0) {
    const char* name = link->Attribute("name");
    throw ConfigError(source_name + ": link '" + (name ? name : "?") + "': <mass value=\"" + value +
                      "\"> must be a finite number of kilograms >= 0 (0 or no <inertial> leaves a moving link out, "
                      "as Gazebo does)");
  }
  return number;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "'" : ", '") + name + "'";
  return out;
}

class Pruner {
 public:
  Pruner(tinyxml2::XMLElement* robot, std::string source_name)
      : robot_(robot), source_name_(std::move(source_name)) {}

  // False when the links and joints do not form a tree this can walk.
  bool read() {
    for (auto* l = robot_->FirstChildElement("link"); l != nullptr; l = l->NextSiblingElement("link")) {
      const char* name = l->Attribute("name");
      if (name == nullptr || !mass_.emplace(name, linkMass(l, source_name_)).second) return false;
      link_order_.emplace_back(name);
    }
    for (auto* j = robot_->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
      const char* name = j->Attribute("name");
      const char* type = j->Attribute("type");
      const auto* parent = j->FirstChildElement("parent");
      const auto* child = j->FirstChildElement("child");
      const char* parent_link = parent ? parent->Attribute("link") : nullptr;
      const char* child_link = child ? child->Attribute("link") : nullptr;
      if (name == nullptr || type == nullptr || parent_link == nullptr || child_link == nullptr) return false;
      if (mass_.count(parent_link) == 0 || mass_.count(child_link) == 0) return false;
      JointEdge edge{name, parent_link, child_link, std::string_view(type) == "fixed"};
      if (!parent_joint_.emplace(edge.child, edge).second) return false;
      children_.emplace(edge.parent, edge);
    }
    // A tree: exactly one root, every link reached from it.
    std::vector<std::string> roots;
    for (const auto& link : link_order_) {
      if (parent_joint_.count(link) == 0) roots.push_back(link);
    }
    if (roots.size() != 1) return false;
    root_ = roots.front();
    std::size_t reached = 0;
    std::vector<std::string> stack{roots.front()};
    while (!stack.empty()) {
      const std::string link = stack.back();
      stack.pop_back();
      if (++reached > link_order_.size()) return false;
      auto range = children_.equal_range(link);
      for (auto it = range.first; it != range.second; ++it) stack.push_back(it->second.child);
    }
    return reached == link_order_.size();
  }

  // Finds the massless moving bodies, top down (depth first, children in
  // document order), and what goes with them. With an explicit stack rather
  // than a recursion per link, which would overflow the call stack on a
  // chain of thousands of links.
  void decide() {
    std::vector<std::string> stack{root_};
    while (!stack.empty()) {
      const std::string link = std::move(stack.back());
      stack.pop_back();
      const auto joint = parent_joint_.find(link);
      if (joint != parent_joint_.end() && !joint->second.fixed && !(bodyMass(link) > 0.0)) {
        std::vector<std::string> below = drop(link);
        below.erase(below.begin());  // the link itself
        warn(link, joint->second.name, below);
        continue;
      }
      pushChildren(link, stack);
    }
  }

  void apply(SimulatableUrdf& result) {
    std::vector<tinyxml2::XMLElement*> remove;
    for (auto* e = robot_->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string_view tag = e->Name();
      const char* name = e->Attribute("name");
      if (tag == "link" && name && dropped_links_.count(name)) {
        result.skipped_links.emplace_back(name);
        remove.push_back(e);
      } else if (tag == "joint" && name && dropped_joints_.count(name)) {
        result.skipped_joints.emplace_back(name);
        remove.push_back(e);
      } else if (tag == "transmission" && namesDroppedJoint(e)) {
        const std::string label = name ? name : "?";
        result.skipped_transmissions.push_back(label);
        logger().warn("{}: transmission '{}' drives a joint left out with its massless link; it is skipped",
                      source_name_, label);
        remove.push_back(e);
      }
    }
    for (auto* e : remove) robot_->DeleteChild(e);
  }

  bool anyDropped() const { return !dropped_links_.empty(); }

 private:
  // The children of `link` onto a depth-first stack, the first on top, so
  // that they come off in document order.
  void pushChildren(const std::string& link, std::vector<std::string>& stack) const {
    const auto range = children_.equal_range(link);
    for (auto it = std::make_reverse_iterator(range.second); it != std::make_reverse_iterator(range.first); ++it) {
      stack.push_back(it->second.child);
    }
  }

  // Mass of the rigid body a link heads: its own plus, in document order, the
  // body mass of each link fixed to it. Each link's partial sum waits on a
  // stack of its own (not the call stack) while its fixed children are
  // summed, so the additions are those of the recursive definition, in the
  // same order.
  double bodyMass(const std::string& link) const {
    struct Partial {
      std::multimap<std::string, JointEdge>::const_iterator next_child, end;
      double mass;
    };
    std::vector<Partial> stack;
    const auto open = [&](const std::string& l) {
      const auto range = children_.equal_range(l);
      stack.push_back(Partial{range.first, range.second, mass_.at(l)});
    };
    open(link);
    while (true) {
      Partial& top = stack.back();
      while (top.next_child != top.end && !top.next_child->second.fixed) ++top.next_child;
      if (top.next_child != top.end) {
        const std::string& child = top.next_child->second.child;
        ++top.next_child;
        open(child);  // (`top` is not used after this: the push may move it)
        continue;
      }
      const double mass = top.mass;
      stack.pop_back();
      if (stack.empty()) return mass;
      stack.back().mass += mass;
    }
  }

  // Leaves out `link`, its joint and everything below it; returns the links
  // left out, depth first in document order, `link` first.
  std::vector<std::string> drop(const std::string& link) {
    std::vector<std::string> dropped;
    std::vector<std::string> stack{link};
    while (!stack.empty()) {
      const std::string next = std::move(stack.back());
      stack.pop_back();
      dropped_links_.insert(next);
      dropped_joints_.insert(parent_joint_.at(next).name);
      pushChildren(next, stack);
      dropped.push_back(next);
    }
    return dropped;
  }

  bool namesDroppedJoint(const tinyxml2::XMLElement* transmission) const {
    for (auto* j = transmission->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
      const char* name = j->Attribute("name");
      if (name && dropped_joints_.count(name)) return true;
    }
    return false;
  }

  void warn(const std::string& link, const std::string& joint, const std::vector<std::string>& below) const {
    const bool has_inertial = mass_.at(link) != 0.0 || hasInertialElement(link);
    logger().warn(
        "{}: link '{}' (moved by joint '{}') has {}, so it cannot be simulated; it is left out with joint '{}'{}, "
        "as Gazebo does. Add <inertial> with <mass value> > 0 and an <inertia> to keep it",
        source_name_, link, joint, has_inertial ? "no mass (<inertial><mass> <= 0)" : "no <inertial>", joint,
        below.empty() ? std::string() : " and what hangs below it (links " + joinNames(below) + ")");
  }

  bool hasInertialElement(const std::string& link) const {
    for (auto* l = robot_->FirstChildElement("link"); l != nullptr; l = l->NextSiblingElement("link")) {
      const char* name = l->Attribute("name");
      if (name && link == name) return l->FirstChildElement("inertial") != nullptr;
    }
    return false;
  }

  tinyxml2::XMLElement* robot_;
  std::string source_name_;
  std::string root_;
  std::vector<std::string> link_order_;
  std::map<std::string, double> mass_;
  std::map<std::string, JointEdge> parent_joint_;    // child link -> joint
  std::multimap<std::string, JointEdge> children_;  // parent link -> joints
  std::set<std::string> dropped_links_;
  std::set<std::string> dropped_joints_;
};

}  // namespace

SimulatableUrdf simulatableUrdf(const std::string& xml, const std::string& source_name) {
  SimulatableUrdf result;
  result.xml = xml;
  tinyxml2::XMLDocument document;
  if (document.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) return result;
  tinyxml2::XMLElement* robot = document.RootElement();
  if (robot == nullptr || std::string_view(robot->Name()) != "robot") return result;
  Pruner pruner(robot, source_name);
  if (!pruner.read()) return result;
  pruner.decide();
  if (!pruner.anyDropped()) return result;
  pruner.apply(result);
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  result.xml = printer.CStr();
  return result;
}

}  // namespace servoloop
