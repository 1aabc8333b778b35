// SDFormat worlds through libsdformat 12 (sdf_world.hpp): the world's
// settings, and each model written as a URDF.
//
// A module of its own (libservoloop_sdf_reader.so, beside servoloop's
// plugins), loaded by readSdfWorld() the first time a world file is read:
// libsdformat's static initialisers cost about 50 ms of CPU at every start of
// a program that links it, which every `servoloop` command and the Python
// package would pay without a world file in sight.
#include "servoloop/description/sdf_world.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <fmt/format.h>
#include <sdf/sdf.hh>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/xml_escape.hpp"

namespace servoloop {
namespace fs = std::filesystem;

// Named, not anonymous: the unity build puts this file beside others with helpers of their own.
namespace sdf_reading {

// Gazebo's own ground_plane and sun models, which every world includes:
// written once per process into a folder of its own, and found there.
constexpr const char* kModelConfig = R"(<?xml version="1.0"?>
<model><name>{}</name><version>1.0</version><sdf version="1.6">model.sdf</sdf>
<description>servoloop's built-in {}</description></model>
)";
constexpr const char* kGroundPlane = R"(<?xml version="1.0"?>
<sdf version="1.6"><model name="ground_plane"><static>true</static><link name="link">
<collision name="collision"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
<surface><friction><ode><mu>100</mu><mu2>50</mu2></ode></friction></surface></collision>
<visual name="visual"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></visual>
</link></model></sdf>
)";
constexpr const char* kSun = R"(<?xml version="1.0"?>
<sdf version="1.6"><light type="directional" name="sun"><cast_shadows>true</cast_shadows>
<pose>0 0 10 0 0 0</pose><diffuse>0.8 0.8 0.8 1</diffuse><specular>0.2 0.2 0.2 1</specular>
<attenuation><range>1000</range><constant>0.9</constant><linear>0.01</linear><quadratic>0.001</quadratic></attenuation>
<direction>-0.5 0.1 -0.9</direction></light></sdf>
)";

const fs::path& builtInModels() {
  static std::once_flag once;
  static fs::path folder;
  std::call_once(once, [] {
    folder = fs::temp_directory_path() / fmt::format("servoloop-sdf-models-{}", ::getpid());
    for (const auto& [name, sdf] : {std::pair{"ground_plane", kGroundPlane}, std::pair{"sun", kSun}}) {
      fs::create_directories(folder / name);
      std::ofstream(folder / name / "model.config") << fmt::format(kModelConfig, name, name);
      std::ofstream(folder / name / "model.sdf") << sdf;
    }
  });
  return folder;
}

std::string errorsText(const sdf::Errors& errors) {
  std::string text;
  for (const sdf::Error& error : errors) {
    std::string where;
    if (error.FilePath()) where = *error.FilePath();
    if (error.LineNumber()) where += fmt::format(":{}", *error.LineNumber());
    text += fmt::format("\n  {}{}", where.empty() ? "" : where + ": ", error.Message());
  }
  return text;
}

Eigen::Isometry3d toEigen(const ignition::math::Pose3d& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = Eigen::Vector3d(pose.Pos().X(), pose.Pos().Y(), pose.Pos().Z());
  out.linear() = Eigen::Quaterniond(pose.Rot().W(), pose.Rot().X(), pose.Rot().Y(), pose.Rot().Z())
                     .normalized()
                     .toRotationMatrix();
  return out;
}

// URDF's rpy of a rotation: R = Rz(yaw) Ry(pitch) Rx(roll).
std::array<double, 3> rollPitchYaw(const Eigen::Matrix3d& r) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  return {roll, pitch, yaw};
}

std::string origin(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d p = pose.translation();
  const auto rpy = rollPitchYaw(pose.linear());
  return fmt::format(R"(<origin xyz="{} {} {}" rpy="{} {} {}"/>)", p.x(), p.y(), p.z(), rpy[0], rpy[1], rpy[2]);
}

// A pose resolved in the model's frame; the error names what it belongs to.
Eigen::Isometry3d inModel(const sdf::SemanticPose& pose, const std::string& what) {
  ignition::math::Pose3d resolved;
  if (const sdf::Errors errors = pose.Resolve(resolved, "__model__"); !errors.empty()) {
    throw ConfigError(fmt::format("{}: its pose cannot be resolved:{}", what, errorsText(errors)));
  }
  return toEigen(resolved);
}

// The child element `path` (e.g. {"surface", "friction", "ode"}) of `element`
// if every step is there, else nullptr (without creating defaults).
sdf::ElementPtr child(sdf::ElementPtr element, std::initializer_list<const char*> path) {
  for (const char* name : path) {
    if (!element || !element->HasElement(name)) return nullptr;
    element = element->GetElement(name);
  }
  return element;
}

struct Friction {
  double mu = 1.0;
  double mu2 = 1.0;
  bool given = false;
};

Friction frictionOf(const sdf::Collision& collision) {
  Friction friction;
  if (sdf::ElementPtr ode = child(collision.Element(), {"surface", "friction", "ode"})) {
    if (ode->HasElement("mu")) friction.mu = ode->Get<double>("mu");
    friction.mu2 = ode->HasElement("mu2") ? ode->Get<double>("mu2") : friction.mu;
    friction.given = true;
  }
  return friction;
}

// Names that become ROS names (the robot's namespace): letters, digits, '_'.
std::string rosName(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out.front()))) out.insert(0, "m_");
  return out;
}

class ModelWriter {
 public:
  ModelWriter(const sdf::Model& model, const fs::path& world_file, const sdf::ParserConfig& config,
              std::vector<std::string>& warnings)
      : model_(model), world_file_(world_file), config_(config), warnings_(warnings),
        where_(fmt::format("{}: model '{}'", world_file.string(), model.Name())) {}

  // The URDF of the model, its root link's pose in the model frame and
  // whether a fixed joint welds it to the world.
  std::string write(Eigen::Isometry3d& root_in_model, bool& welded) {
    const sdf::Link* root = model_.CanonicalLink();
    if (root == nullptr) throw ConfigError(where_ + " has no link; give it at least one <link>");
    // The tree: every joint from its parent link to its child link.
    std::map<std::string, const sdf::Joint*> joint_of_child;
    welded = false;
    for (std::uint64_t j = 0; j < model_.JointCount(); ++j) {
      const sdf::Joint* joint = model_.JointByIndex(j);
      std::string parent;
      std::string child_link;
      joint->ResolveParentLink(parent);
      joint->ResolveChildLink(child_link);
      if (parent == "world") {
        if (joint->Type() != sdf::JointType::FIXED) {
          throw ConfigError(fmt::format("{}: joint '{}' joins link '{}' to the world and moves ({}); servoloop "
                                        "welds a model to the world only with a fixed joint (or <static>)",
                                        where_, joint->Name(), child_link, jointTypeName(joint->Type())));
        }
        welded = true;
        continue;
      }
      if (!joint_of_child.emplace(child_link, joint).second) {
        throw ConfigError(fmt::format("{}: link '{}' is the child of two joints; a model's links must form a tree",
                                      where_, child_link));
      }
    }
    // Each link's URDF frame: the root's own frame, or the frame of the
    // joint that moves it (URDF places a child link at its joint).
    const bool fixed = model_.Static() || welded;
    std::vector<std::string> welded_links;
    for (std::uint64_t l = 0; l < model_.LinkCount(); ++l) {
      const sdf::Link* link = model_.LinkByIndex(l);
      const auto it = joint_of_child.find(link->Name());
      if (link != root && it == joint_of_child.end() && fixed) {
        // A static model's links stand where they are: fixed to the root.
        frames_[link->Name()] = inModel(link->SemanticPose(), where_ + " link '" + link->Name() + "'");
        welded_links.push_back(link->Name());
        continue;
      }
      if (link != root && it == joint_of_child.end()) {
        throw ConfigError(fmt::format("{}: link '{}' is not joined to the canonical link '{}'; servoloop simulates "
                                      "a model's links as one tree (join them, or make it a model of its own)",
                                      where_, link->Name(), root->Name()));
      }
      frames_[link->Name()] = link == root ? inModel(link->SemanticPose(), where_ + " link '" + link->Name() + "'")
                                           : inModel(it->second->SemanticPose(),
                                                     where_ + " joint '" + it->second->Name() + "'");
    }
    std::string urdf = fmt::format("<?xml version=\"1.0\"?>\n<robot name=\"{}\">\n", xmlEscape(model_.Name()));
    for (std::uint64_t l = 0; l < model_.LinkCount(); ++l) urdf += link(*model_.LinkByIndex(l));
    for (const auto& [child_link, joint] : joint_of_child) urdf += this->joint(*joint, child_link);
    for (const std::string& link : welded_links) {
      urdf += fmt::format("  <joint name=\"{}_to_{}\" type=\"fixed\">{}<parent link=\"{}\"/><child link=\"{}\"/></joint>\n",
                          xmlEscape(root->Name()), xmlEscape(link),
                          origin(frames_.at(root->Name()).inverse() * frames_.at(link)), xmlEscape(root->Name()),
                          xmlEscape(link));
    }
    urdf += gazebo_;
    urdf += "</robot>\n";
    root_in_model = frames_.at(root->Name());
    return urdf;
  }

 private:
  static const char* jointTypeName(sdf::JointType type) {
    switch (type) {
      case sdf::JointType::BALL: return "ball";
      case sdf::JointType::CONTINUOUS: return "continuous";
      case sdf::JointType::FIXED: return "fixed";
      case sdf::JointType::GEARBOX: return "gearbox";
      case sdf::JointType::PRISMATIC: return "prismatic";
      case sdf::JointType::REVOLUTE: return "revolute";
      case sdf::JointType::REVOLUTE2: return "revolute2";
      case sdf::JointType::SCREW: return "screw";
      case sdf::JointType::UNIVERSAL: return "universal";
      default: return "invalid";
    }
  }

  // The geometry as URDF, or "" (with a warning) for one it has no form of.
  std::string geometry(const sdf::Geometry& geometry, const std::string& what) {
    switch (geometry.Type()) {
      case sdf::GeometryType::BOX: {
        const auto size = geometry.BoxShape()->Size();
        return fmt::format(R"(<box size="{} {} {}"/>)", size.X(), size.Y(), size.Z());
      }
      case sdf::GeometryType::CYLINDER:
        return fmt::format(R"(<cylinder radius="{}" length="{}"/>)", geometry.CylinderShape()->Radius(),
                           geometry.CylinderShape()->Length());
      case sdf::GeometryType::SPHERE:
        return fmt::format(R"(<sphere radius="{}"/>)", geometry.SphereShape()->Radius());
      case sdf::GeometryType::MESH: {
        const sdf::Mesh& mesh = *geometry.MeshShape();
        const std::string file = meshFile(mesh, what);
        const auto scale = mesh.Scale();
        return fmt::format(R"(<mesh filename="{}" scale="{} {} {}"/>)", xmlEscape(file), scale.X(), scale.Y(),
                           scale.Z());
      }
      case sdf::GeometryType::PLANE:
        warnings_.push_back(fmt::format("{}: {}: a plane is simulated only as the world's ground (a static model "
                                        "whose plane faces up through the origin); left out",
                                        where_, what));
        return "";
      default:
        warnings_.push_back(fmt::format("{}: {}: this geometry (capsule, ellipsoid, heightmap, polyline) is not "
                                        "simulated; left out",
                                        where_, what));
        return "";
    }
  }

  std::string meshFile(const sdf::Mesh& mesh, const std::string& what) {
    const std::string uri = mesh.Uri();
    std::string found;
    if (uri.rfind("model://", 0) == 0) {
      found = sdf::findFile(uri, true, false, config_);
    } else {
      fs::path path = uri.rfind("file://", 0) == 0 ? fs::path(uri.substr(7)) : fs::path(uri);
      if (path.is_relative()) path = fs::path(mesh.FilePath().empty() ? world_file_.string() : mesh.FilePath()).parent_path() / path;
      found = path.lexically_normal().string();
    }
    std::error_code ec;
    if (found.empty() || !fs::is_regular_file(found, ec)) {
      throw ConfigError(fmt::format("{}: {}: mesh '{}' not found (model:// URIs are looked for in GAZEBO_MODEL_PATH "
                                    "and SDF_PATH; other paths relative to the file that names them)",
                                    where_, what, uri));
    }
    return fs::absolute(found).lexically_normal().string();
  }

  std::string link(const sdf::Link& link) {
    const std::string what = "link '" + link.Name() + "'";
    const Eigen::Isometry3d frame = frames_.at(link.Name());
    const Eigen::Isometry3d link_in_model = inModel(link.SemanticPose(), where_ + " " + what);
    const Eigen::Isometry3d to_frame = frame.inverse() * link_in_model;
    std::string out = fmt::format("  <link name=\"{}\">\n", xmlEscape(link.Name()));
    const ignition::math::Inertiald& inertial = link.Inertial();
    const auto& mass = inertial.MassMatrix();
    const auto diagonal = mass.DiagonalMoments();
    const auto off = mass.OffDiagonalMoments();
    out += fmt::format(
        "    <inertial>{}<mass value=\"{}\"/><inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" "
        "izz=\"{}\"/></inertial>\n",
        origin(to_frame * toEigen(inertial.Pose())), mass.Mass(), diagonal.X(), off.X(), off.Y(), diagonal.Y(),
        off.Z(), diagonal.Z());
    std::optional<Friction> friction;
    for (std::uint64_t c = 0; c < link.CollisionCount(); ++c) {
      const sdf::Collision& collision = *link.CollisionByIndex(c);
      const std::string part = what + " collision '" + collision.Name() + "'";
      const std::string shape = geometry(*collision.Geom(), part);
      if (shape.empty()) continue;
      const Eigen::Isometry3d pose = frame.inverse() * inModel(collision.SemanticPose(), where_ + " " + part);
      out += fmt::format("    <collision name=\"{}\">{}<geometry>{}</geometry></collision>\n",
                         xmlEscape(collision.Name()), origin(pose), shape);
      const Friction f = frictionOf(collision);
      if (!friction) {
        friction = f;
      } else if (f.mu != friction->mu || f.mu2 != friction->mu2) {
        warnings_.push_back(fmt::format("{}: {}: collisions of one link with different friction; servoloop takes "
                                        "one per link (mu {} of the first)",
                                        where_, what, friction->mu));
      }
    }
    for (std::uint64_t v = 0; v < link.VisualCount(); ++v) {
      const sdf::Visual& visual = *link.VisualByIndex(v);
      const std::string part = what + " visual '" + visual.Name() + "'";
      const std::string shape = visual.Geom() == nullptr ? "" : geometry(*visual.Geom(), part);
      if (shape.empty()) continue;
      const Eigen::Isometry3d pose = frame.inverse() * inModel(visual.SemanticPose(), where_ + " " + part);
      std::string material;
      if (const sdf::Material* m = visual.Material()) {
        const auto colour = m->Diffuse();
        material = fmt::format(R"(<material name="{}_{}"><color rgba="{} {} {} {}"/></material>)",
                               xmlEscape(link.Name()), v, colour.R(), colour.G(), colour.B(), colour.A());
      }
      out += fmt::format("    <visual name=\"{}\">{}<geometry>{}</geometry>{}</visual>\n", xmlEscape(visual.Name()),
                         origin(pose), shape, material);
    }
    for (std::uint64_t s = 0; s < link.SensorCount(); ++s) {
      warnings_.push_back(fmt::format("{}: {}: sensor '{}' is not simulated; left out", where_, what,
                                      link.SensorByIndex(s)->Name()));
    }
    for (std::uint64_t s = 0; s < link.LightCount(); ++s) {
      warnings_.push_back(fmt::format("{}: {}: light '{}' is not simulated; left out", where_, what,
                                      link.LightByIndex(s)->Name()));
    }
    out += "  </link>\n";
    if (friction && friction->given) {
      gazebo_ += fmt::format("  <gazebo reference=\"{}\"><mu1>{}</mu1><mu2>{}</mu2></gazebo>\n",
                             xmlEscape(link.Name()), friction->mu, friction->mu2);
    }
    return out;
  }

  std::string joint(const sdf::Joint& joint, const std::string& child_link) {
    std::string parent;
    joint.ResolveParentLink(parent);
    const std::string what = fmt::format("{} joint '{}'", where_, joint.Name());
    std::string type;
    switch (joint.Type()) {
      case sdf::JointType::FIXED: type = "fixed"; break;
      case sdf::JointType::PRISMATIC: type = "prismatic"; break;
      case sdf::JointType::REVOLUTE: type = "revolute"; break;
      case sdf::JointType::CONTINUOUS: type = "continuous"; break;
      default:
        throw ConfigError(fmt::format("{}: a {} joint has no URDF form servoloop simulates; use revolute, "
                                      "continuous, prismatic or fixed joints",
                                      what, jointTypeName(joint.Type())));
    }
    const sdf::JointAxis* axis = joint.Axis(0);
    if (type == "revolute" && axis != nullptr && axis->Lower() <= -1e15 && axis->Upper() >= 1e15) type = "continuous";
    const Eigen::Isometry3d pose = frames_.at(parent).inverse() * frames_.at(child_link);
    std::string out = fmt::format("  <joint name=\"{}\" type=\"{}\">{}<parent link=\"{}\"/><child link=\"{}\"/>",
                                  xmlEscape(joint.Name()), type, origin(pose), xmlEscape(parent),
                                  xmlEscape(child_link));
    if (type != "fixed" && axis != nullptr) {
      ignition::math::Vector3d xyz;
      if (const sdf::Errors errors = axis->ResolveXyz(xyz); !errors.empty()) {
        throw ConfigError(fmt::format("{}: its axis cannot be resolved:{}", what, errorsText(errors)));
      }
      out += fmt::format(R"(<axis xyz="{} {} {}"/>)", xyz.X(), xyz.Y(), xyz.Z());
      const double effort = axis->Effort() >= 0.0 ? axis->Effort() : 1e6;
      const double velocity = axis->MaxVelocity() >= 0.0 ? axis->MaxVelocity() : 1e6;
      if (type == "continuous") {
        out += fmt::format(R"(<limit effort="{}" velocity="{}"/>)", effort, velocity);
      } else {
        out += fmt::format(R"(<limit lower="{}" upper="{}" effort="{}" velocity="{}"/>)", axis->Lower(),
                           axis->Upper(), effort, velocity);
      }
      out += fmt::format(R"(<dynamics damping="{}" friction="{}"/>)", axis->Damping(), axis->Friction());
    }
    return out + "</joint>\n";
  }

  const sdf::Model& model_;
  fs::path world_file_;
  const sdf::ParserConfig& config_;
  std::vector<std::string>& warnings_;
  std::string where_;
  std::map<std::string, Eigen::Isometry3d> frames_;  // each link's URDF frame in the model frame
  std::string gazebo_;                              // <gazebo reference> blocks
};

// A static model whose every collision is a plane facing up through the
// world's origin: the world's ground plane.
bool isGroundPlane(const sdf::Model& model, const Eigen::Isometry3d& model_in_world) {
  if (!model.Static() || model.LinkCount() == 0) return false;
  bool any_plane = false;
  for (std::uint64_t l = 0; l < model.LinkCount(); ++l) {
    const sdf::Link& link = *model.LinkByIndex(l);
    for (std::uint64_t c = 0; c < link.CollisionCount(); ++c) {
      const sdf::Collision& collision = *link.CollisionByIndex(c);
      if (collision.Geom()->Type() != sdf::GeometryType::PLANE) return false;
      ignition::math::Pose3d pose;
      if (!collision.SemanticPose().Resolve(pose, "__model__").empty()) return false;
      const Eigen::Isometry3d in_world = model_in_world * toEigen(pose);
      const auto normal = collision.Geom()->PlaneShape()->Normal();
      const Eigen::Vector3d up = in_world.linear() * Eigen::Vector3d(normal.X(), normal.Y(), normal.Z()).normalized();
      if (up.z() < 1.0 - 1e-9 || std::abs(in_world.translation().z()) > 1e-9) return false;
      any_plane = true;
    }
  }
  return any_plane;
}

// The lines libsdformat printed ("Error [Param.cc:598] The value ..."), its
// colour codes left out, sorted into errors and warnings.
void consolePrinted(const std::string& text, std::vector<std::string>& errors, std::vector<std::string>& warnings) {
  std::string plain;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\x1b') {
      while (i < text.size() && text[i] != 'm') ++i;
      continue;
    }
    plain += text[i];
  }
  std::istringstream lines(plain);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t close = line.find("] ");
    const std::string message = close == std::string::npos ? line : line.substr(close + 2);
    if (message.empty()) continue;
    if (line.rfind("Error", 0) == 0) errors.push_back(message);
    if (line.rfind("Warning", 0) == 0) warnings.push_back(message);
  }
}

void warnPlugins(const sdf::ElementPtr& element, const std::string& where, std::vector<std::string>& warnings) {
  if (!element || !element->HasElement("plugin")) return;
  for (sdf::ElementPtr plugin = element->GetElement("plugin"); plugin; plugin = plugin->GetNextElement("plugin")) {
    const std::string name = plugin->HasAttribute("name") ? plugin->GetAttribute("name")->GetAsString() : "";
    const std::string file = plugin->HasAttribute("filename") ? plugin->GetAttribute("filename")->GetAsString() : "";
    warnings.push_back(fmt::format("{}: plugin '{}' ({}) is a Gazebo plugin; servoloop does not load it", where, name,
                                   file));
  }
}

}  // namespace sdf_reading

using namespace sdf_reading;

static SdfWorld readSdfWorldWithLibsdformat(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw ConfigError(fmt::format("world file '{}' cannot be read (no such file); check the path", file.string()));
  }
  const fs::path absolute = fs::absolute(file).lexically_normal();
  sdf::ParserConfig config;
  for (const char* variable : {"GAZEBO_MODEL_PATH", "SDF_PATH"}) {
    if (const char* paths = std::getenv(variable); paths != nullptr && *paths != '\0') {
      config.AddURIPath("model://", paths);
    }
  }
  config.AddURIPath("model://", builtInModels().string());
  sdf::Root root;
  sdf::Errors errors;
  std::vector<std::string> console_errors;
  std::vector<std::string> console_warnings;
  {
    // libsdformat prints some of its findings (which value was wrong) on
    // std::cerr instead of returning them, and its URDF check prints through
    // console_bridge: both are taken here, so that each is said once, in the
    // error or among the warnings.
    static std::mutex console_mutex;
    const std::lock_guard lock(console_mutex);
    struct Discard : console_bridge::OutputHandler {
      void log(const std::string&, console_bridge::LogLevel, const char*, int) override {}
    } discard;
    console_bridge::useOutputHandler(&discard);
    std::ostringstream printed;
    std::streambuf* const cerr = std::cerr.rdbuf(printed.rdbuf());
    try {
      errors = root.Load(absolute.string(), config);
    } catch (...) {
      std::cerr.rdbuf(cerr);
      console_bridge::restorePreviousOutputHandler();
      throw;
    }
    std::cerr.rdbuf(cerr);
    console_bridge::restorePreviousOutputHandler();
    consolePrinted(printed.str(), console_errors, console_warnings);
  }
  if (!errors.empty()) {
    std::string said;
    for (const std::string& line : console_errors) said += "\n  " + line;
    throw ConfigError(fmt::format("{}: libsdformat cannot read it:{}{}", absolute.string(), said, errorsText(errors)));
  }
  if (root.WorldCount() == 0) {
    throw ConfigError(fmt::format("{}: holds no <world>; a world file has one <world> with its <model>s",
                                  absolute.string()));
  }
  SdfWorld world;
  for (const std::string& warning : console_warnings) {
    world.warnings.push_back(fmt::format("{}: libsdformat: {}", absolute.string(), warning));
  }
  const sdf::World& w = *root.WorldByIndex(0);
  world.name = w.Name();
  if (root.WorldCount() > 1) {
    world.warnings.push_back(fmt::format("{}: {} worlds; servoloop reads the first ('{}')", absolute.string(),
                                         root.WorldCount(), w.Name()));
  }
  const std::string where = fmt::format("{}: world '{}'", absolute.string(), w.Name());
  if (const sdf::Physics* physics = w.PhysicsDefault()) {
    world.time_step_s = physics->MaxStepSize();
  }
  const auto gravity = w.Gravity();
  world.gravity = {gravity.X(), gravity.Y(), gravity.Z()};
  for (std::uint64_t l = 0; l < w.LightCount(); ++l) {
    world.warnings.push_back(fmt::format("{}: light '{}' is not simulated (servoloop draws no images)", where,
                                         w.LightByIndex(l)->Name()));
  }
  for (std::uint64_t a = 0; a < w.ActorCount(); ++a) {
    world.warnings.push_back(fmt::format("{}: actor '{}' is not simulated; left out", where,
                                         w.ActorByIndex(a)->Name()));
  }
  if (w.Gui() != nullptr) world.warnings.push_back(where + ": <gui> is Gazebo's window; servoloop has none");
  warnPlugins(w.Element(), where, world.warnings);

  std::set<std::string> names;
  for (std::uint64_t m = 0; m < w.ModelCount(); ++m) {
    const sdf::Model& model = *w.ModelByIndex(m);
    ignition::math::Pose3d model_pose;
    if (const sdf::Errors errors = model.SemanticPose().Resolve(model_pose); !errors.empty()) {
      throw ConfigError(fmt::format("{}: model '{}': its pose cannot be resolved:{}", absolute.string(), model.Name(),
                                    errorsText(errors)));
    }
    const Eigen::Isometry3d model_in_world = toEigen(model_pose);
    if (isGroundPlane(model, model_in_world)) {
      world.ground_plane = true;
      continue;
    }
    const std::string model_where = fmt::format("{}: model '{}'", absolute.string(), model.Name());
    for (std::uint64_t n = 0; n < model.ModelCount(); ++n) {
      world.warnings.push_back(fmt::format("{}: nested model '{}' is not simulated; make it a model of the world",
                                           model_where, model.ModelByIndex(n)->Name()));
    }
    warnPlugins(model.Element(), model_where, world.warnings);
    SdfWorldModel out;
    out.name = rosName(model.Name());
    if (!names.insert(out.name).second) {
      throw ConfigError(fmt::format("{}: two models are named '{}'; give each its own name", absolute.string(),
                                    out.name));
    }
    Eigen::Isometry3d root_in_model = Eigen::Isometry3d::Identity();
    bool welded = false;
    out.urdf = ModelWriter(model, absolute, config, world.warnings).write(root_in_model, welded);
    out.fixed_base = model.Static() || welded;
    const Eigen::Isometry3d root_in_world = model_in_world * root_in_model;
    const auto rpy = rollPitchYaw(root_in_world.linear());
    out.pose = {root_in_world.translation().x(), root_in_world.translation().y(), root_in_world.translation().z(),
                rpy[0], rpy[1], rpy[2]};
    world.models.push_back(std::move(out));
  }
  return world;
}

}  // namespace servoloop

// The module's entry (sdf_world.cpp looks it up by this name). Exceptions
// (ConfigError) pass to the caller: both sides share the C++ runtime.
extern "C" __attribute__((visibility("default"))) void servoloop_read_sdf_world(const std::filesystem::path& file,
                                                                                 servoloop::SdfWorld& world) {
  world = servoloop::readSdfWorldWithLibsdformat(file);
}
