#include "servoloop/description/gazebo_sensors.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop {
namespace {

using tinyxml2::XMLElement;

// The sensor types Gazebo knows that servoloop leaves out: Gazebo classic's
// (SDFormat 1.6 and its thermal camera) and the names newer SDFormat gives
// some of them, so that a URDF written for either loads.
constexpr std::string_view kLeftOutTypes[] = {
    "camera", "multicamera", "depth", "ray", "gpu_ray", "gps", "altimeter", "magnetometer", "sonar", "rfid",
    "rfidtag", "wireless_receiver", "wireless_transmitter", "logical_camera", "thermal_camera",
    // SDFormat 1.7 on (Ignition Gazebo).
    "depth_camera", "rgbd_camera", "gpu_lidar", "lidar", "navsat", "air_pressure", "segmentation_camera",
    "boundingbox_camera"};

// Gazebo's name for each part of a link's geometry once it is in SDFormat:
// "<link>_collision", "<link>_collision_<n>", the old "<link>_geom", and
// "<body>_fixed_joint_lump__<link>_collision" when a fixed joint merges the
// link into <body>.
constexpr std::string_view kLumpMarker = "_fixed_joint_lump__";

std::optional<SensorType> simulatedType(std::string_view type) {
  if (type == "imu") return SensorType::imu;
  if (type == "force_torque") return SensorType::force_torque;
  if (type == "contact") return SensorType::contact;
  return std::nullopt;
}

bool isLeftOutType(std::string_view type) {
  for (const std::string_view known : kLeftOutTypes) {
    if (type == known) return true;
  }
  return false;
}

std::string leftOutTypeList() {
  std::string out;
  for (const std::string_view known : kLeftOutTypes) out += (out.empty() ? "" : ", ") + std::string(known);
  return out;
}

std::string_view trim(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

bool startsWith(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// The element's text, trimmed; "" when it has none.
std::string textOf(const XMLElement& element) {
  const char* text = element.GetText();
  return std::string(trim(text == nullptr ? "" : text));
}

// One finite number, the whole of `text` (leading "+" allowed, as SDFormat
// allows it); nullopt otherwise.
std::optional<double> parseNumber(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Whitespace-separated finite numbers; nullopt if any token is not one.
std::optional<std::vector<double>> parseNumbers(std::string_view text) {
  std::vector<double> numbers;
  text = trim(text);
  while (!text.empty()) {
    const std::size_t end = std::min(text.find_first_of(" \t\r\n"), text.size());
    const std::optional<double> number = parseNumber(text.substr(0, end));
    if (!number) return std::nullopt;
    numbers.push_back(*number);
    text = trim(text.substr(end));
  }
  return numbers;
}

// "<imu><angular_velocity><x><noise><stddev>": the elements from below `top` down to `element`.
std::string pathBelow(const XMLElement& top, const XMLElement& element) {
  std::string path;
  for (const XMLElement* at = &element; at != nullptr && at != &top;
       at = at->Parent() != nullptr ? at->Parent()->ToElement() : nullptr) {
    path = "<" + std::string(at->Name()) + ">" + path;
  }
  return path;
}

// The library an element loads, as its file's stem ("gazebo_ros_imu" for
// "libgazebo_ros_imu.so"): <plugin filename="..."> or, from Gazebo before
// 1.0 (PR2's URDF), <controller:gazebo_ros_imu plugin="...">. "" for an
// element that loads none.
std::string pluginStem(const XMLElement& element) {
  const bool plugin = std::string_view(element.Name()) == "plugin";
  const char* file = plugin ? element.Attribute("filename") : element.Attribute("plugin");
  if (file == nullptr) return "";
  std::string_view stem = trim(file);
  if (const std::size_t slash = stem.rfind('/'); slash != std::string_view::npos) stem.remove_prefix(slash + 1);
  if (startsWith(stem, "lib")) stem.remove_prefix(3);
  if (stem.size() > 3 && stem.substr(stem.size() - 3) == ".so") stem.remove_suffix(3);
  return std::string(stem);
}

// Which plugin settings a sensor reads, by the plugin that gives them.
struct PluginFields {
  const char* topic;  // topicName or bumperTopicName
  const char* rate;   // updateRate or updateRateHZ
};

class SensorReader {
 public:
  SensorReader(const XMLElement& robot, const urdf::ModelInterface& model, const std::string& source_name)
      : model_(model), source_(source_name) {
    for (auto* e = robot.FirstChildElement("link"); e != nullptr; e = e->NextSiblingElement("link")) {
      if (const char* name = e->Attribute("name")) urdf_links_.insert(name);
    }
    for (auto* e = robot.FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
      if (const char* name = e->Attribute("name")) urdf_joints_.insert(name);
    }
  }

  // The <sensor>s of a <gazebo reference="..."> block, and the older
  // <sensor:TYPE> of Gazebo before 1.0.
  void readReferenced(const XMLElement& gazebo, const std::string& reference) {
    for (auto* e = gazebo.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string_view tag = e->Name();
      if (tag == "sensor") {
        const char* type = e->Attribute("type");
        readSensor(*e, reference, false, type == nullptr ? std::nullopt : std::optional<std::string>(type));
      } else if (startsWith(tag, "sensor:")) {
        readSensor(*e, reference, true, std::string(tag.substr(7)));
      }
    }
  }

  // The model plugins of a <gazebo> block without reference that give an
  // IMU or a force-torque sensor.
  void readModelPlugins(const XMLElement& gazebo) {
    for (auto* e = gazebo.FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const std::string stem = pluginStem(*e);
      const std::string_view tag = e->Name();
      if (stem == "gazebo_ros_imu" || stem == "hector_gazebo_ros_imu") {
        readImuPlugin(*e, stem == "hector_gazebo_ros_imu");
      } else if (stem == "gazebo_ros_ft_sensor") {
        readForceTorquePlugin(*e);
      } else if (tag == "sensor" || startsWith(tag, "sensor:")) {
        const char* name = e->Attribute("name");
        logger().warn(
            "{}: <gazebo><{} name='{}'> has no reference, so it belongs to no link or joint and Gazebo does not "
            "load it; it is left out (put it in <gazebo reference='LINK'>, or reference='JOINT' for force_torque)",
            source_, tag, name == nullptr ? "?" : name);
      }
    }
  }

  std::vector<SensorDescription> take() { return std::move(sensors_); }

 private:
  [[noreturn]] static void fail(const std::string& element, const std::string& what) {
    throw ConfigError(element + ": " + what);
  }

  // An error about the value of `at`, an element inside `top`.
  [[noreturn]] static void failValue(const std::string& element, const XMLElement& top, const XMLElement& at,
                                     const std::string& why) {
    throw ConfigError(element + " " + pathBelow(top, at) + " '" + textOf(at) + "': " + why);
  }

  // ---------------------------------------------------------------------------
  // Values.

  static bool readBool(const std::string& element, const XMLElement& top, const XMLElement& at) {
    const std::string text = textOf(at);
    if (text == "true" || text == "1") return true;
    if (text == "false" || text == "0") return false;
    failValue(element, top, at, "must be true, false, 1 or 0");
  }

  static double readRate(const std::string& element, const XMLElement& top, const XMLElement& at) {
    const std::optional<double> rate = parseNumber(textOf(at));
    if (!rate || *rate < 0.0) {
      failValue(element, top, at,
                std::string("an update rate must be a finite number of Hz >= 0 (0: every physics step); write e.g. <") +
                    at.Name() + ">100</" + at.Name() + ">");
    }
    return *rate;
  }

  static double readStddev(const std::string& element, const XMLElement& top, const XMLElement& at) {
    const std::optional<double> stddev = parseNumber(textOf(at));
    if (!stddev || *stddev < 0.0) {
      failValue(element, top, at, "a standard deviation must be a finite number >= 0 (0: no noise)");
    }
    return *stddev;
  }

  static double readFinite(const std::string& element, const XMLElement& top, const XMLElement& at) {
    const std::optional<double> value = parseNumber(textOf(at));
    if (!value) failValue(element, top, at, "must be a finite number");
    return *value;
  }

  // One standard deviation for all three axes, or one per axis (hector's
  // <rateGaussianNoise>0.01 0.01 0.02</rateGaussianNoise>).
  static std::array<double, 3> readStddevPerAxis(const std::string& element, const XMLElement& top,
                                                 const XMLElement& at) {
    const std::optional<std::vector<double>> numbers = parseNumbers(textOf(at));
    const bool counted = numbers && (numbers->size() == 1 || numbers->size() == 3);
    bool non_negative = counted;
    for (std::size_t i = 0; counted && i < numbers->size(); ++i) non_negative = non_negative && (*numbers)[i] >= 0.0;
    if (!non_negative) {
      failValue(element, top, at,
                "must be one standard deviation >= 0 for all axes, or three (x y z), as finite numbers");
    }
    if (numbers->size() == 1) return {numbers->front(), numbers->front(), numbers->front()};
    return {(*numbers)[0], (*numbers)[1], (*numbers)[2]};
  }

  static std::array<double, 6> readPose(const std::string& element, const XMLElement& top, const XMLElement& at) {
    const std::optional<std::vector<double>> numbers = parseNumbers(textOf(at));
    if (!numbers || numbers->size() != 6) {
      failValue(element, top, at,
                "a pose is 6 finite numbers: x y z (m) roll pitch yaw (rad), e.g. <pose>0 0 0.1 0 0 0</pose>");
    }
    std::array<double, 6> pose{};
    std::copy(numbers->begin(), numbers->end(), pose.begin());
    return pose;
  }

  static std::array<double, 3> readVector3(const std::string& element, const XMLElement& top, const XMLElement& at,
                                           const char* meaning) {
    const std::optional<std::vector<double>> numbers = parseNumbers(textOf(at));
    if (!numbers || numbers->size() != 3) {
      failValue(element, top, at, std::string("must be 3 finite numbers: ") + meaning);
    }
    return {(*numbers)[0], (*numbers)[1], (*numbers)[2]};
  }

  // <mean>, <stddev>, <bias_mean> and <bias_stddev> under `holder`; 0 for
  // those not given.
  static GaussianNoise readNoiseValues(const std::string& element, const XMLElement& top, const XMLElement& holder) {
    GaussianNoise noise;
    if (const XMLElement* e = holder.FirstChildElement("mean")) noise.mean = readFinite(element, top, *e);
    if (const XMLElement* e = holder.FirstChildElement("stddev")) noise.stddev = readStddev(element, top, *e);
    if (const XMLElement* e = holder.FirstChildElement("bias_mean")) noise.bias_mean = readFinite(element, top, *e);
    if (const XMLElement* e = holder.FirstChildElement("bias_stddev")) {
      noise.bias_stddev = readStddev(element, top, *e);
    }
    return noise;
  }

  // Whether a <noise> adds noise: type "gaussian" (or "gaussian_quantized",
  // whose quantization is not simulated) does, "none" does not. SDFormat 1.6
  // writes <noise type="...">, 1.4 <noise><type>...</type>.
  static bool noiseIsOn(const std::string& element, const XMLElement& top, const XMLElement& noise) {
    std::string type;
    if (const char* attribute = noise.Attribute("type")) {
      type = trim(attribute);
    } else if (const XMLElement* type_element = noise.FirstChildElement("type")) {
      type = textOf(*type_element);
    }
    if (type == "gaussian" || type == "gaussian_quantized") return true;
    if (type == "none") return false;
    throw ConfigError(element + " " + pathBelow(top, noise) + " type '" + type +
                      "': a noise type is gaussian, gaussian_quantized or none; write <noise type=\"gaussian\">");
  }

  // ---------------------------------------------------------------------------
  // References.

  // Why `name` is no link of the model, and what to do.
  std::string whyNoLink(const std::string& name, SensorType type) const {
    if (const urdf::JointConstSharedPtr joint = model_.getJoint(name)) {
      return "'" + name + "' is a joint, but " + (type == SensorType::imu ? "an imu" : "a contact") +
             " sensor sits on a link; name a link, e.g. the joint's child link '" + joint->child_link_name +
             "' (only force_torque sensors take a joint)";
    }
    if (urdf_links_.count(name) != 0) {
      return "link '" + name +
             "' was left out of the simulated robot: it moves but has no mass (or hangs below such a link), so it "
             "is dropped as Gazebo drops it; give it an <inertial> with <mass> > 0, or put the sensor on a link "
             "that is simulated";
    }
    return "the robot has no link '" + name +
           "' (a link of the URDF may have been left out because it is massless or not connected to the tree, as "
           "Gazebo leaves such links out); name one of the robot's links";
  }

  // Why `name` is no joint of the model, and what to do.
  std::string whyNoJoint(const std::string& name) const {
    if (const urdf::LinkConstSharedPtr link = model_.getLink(name)) {
      return "'" + name + "' is a link, but a force_torque sensor measures a joint; name the joint" +
             (link->parent_joint ? ", e.g. '" + link->parent_joint->name + "' (the one above '" + name + "')" : "");
    }
    if (urdf_joints_.count(name) != 0) {
      return "joint '" + name +
             "' was left out of the simulated robot with its child link, which moves but has no mass (or hangs "
             "below such a link), as Gazebo leaves it out; give that link an <inertial> with <mass> > 0";
    }
    return "the robot has no joint '" + name +
           "' (a joint may have been left out with a massless or unconnected child link, as Gazebo leaves such "
           "links out); name one of the robot's joints";
  }

  // Whether `collision`, one of Gazebo's collision names, is part of
  // `link`'s geometry: its own collisions, those of links fixed below it
  // (which Gazebo merges into it) and, when `link` is itself fixed to a link
  // above, its collisions under the name the merge gives them.
  static bool isCollisionOf(std::string_view collision, const urdf::Link& link) {
    std::vector<const urdf::Link*> merged{&link};
    for (std::size_t i = 0; i < merged.size(); ++i) {
      for (const urdf::LinkSharedPtr& child : merged[i]->child_links) {
        if (child && child->parent_joint && child->parent_joint->type == urdf::Joint::FIXED) {
          merged.push_back(child.get());
        }
      }
    }
    const auto names_own = [&](std::string_view part) {
      for (const urdf::Link* l : merged) {
        if (startsWith(part, l->name + "_collision") || startsWith(part, l->name + "_geom")) return true;
        for (const urdf::CollisionSharedPtr& c : l->collision_array) {
          if (c && !c->name.empty() && part == c->name) return true;
        }
      }
      return false;
    };
    if (names_own(collision)) return true;
    const std::size_t marker = collision.find(kLumpMarker);
    if (marker == std::string_view::npos) return false;
    const std::string_view body = collision.substr(0, marker);
    if (body == link.name) return true;
    // `link` merged into a link above it: "<body>_fixed_joint_lump__<link>_collision".
    bool fixed_to_body = false;
    const urdf::Link* above = &link;
    while (!fixed_to_body && above->parent_joint && above->parent_joint->type == urdf::Joint::FIXED) {
      const urdf::LinkSharedPtr parent = above->getParent();
      if (!parent) break;
      above = parent.get();
      fixed_to_body = above->name == body;
    }
    if (!fixed_to_body) return false;
    std::string_view rest = collision.substr(marker + kLumpMarker.size());
    while (true) {
      const std::size_t next = rest.find(kLumpMarker);
      if (names_own(rest.substr(0, next))) return true;
      if (next == std::string_view::npos) return false;
      rest.remove_prefix(next + kLumpMarker.size());
    }
  }

  // ---------------------------------------------------------------------------
  // <sensor> in <gazebo reference="...">.

  void readSensor(const XMLElement& xml, const std::string& reference, bool legacy,
                  const std::optional<std::string>& type) {
    const char* name = xml.Attribute("name");
    const std::string element = source_ + ": <gazebo reference='" + reference + "'><" + xml.Name() +
                                (name != nullptr ? std::string(" name='") + name + "'" : std::string()) + ">";
    if (name == nullptr || trim(name).empty()) {
      fail(element, "the sensor has no name; give it one of its own, e.g. <sensor name=\"" + reference +
                        "_sensor\" ...> (it names the sensor's handle and topic)");
    }
    if (!type) {
      fail(element, "the sensor has no type; write type=\"imu\", \"force_torque\" or \"contact\" (the types "
                    "servoloop simulates)");
    }
    const std::optional<SensorType> simulated = simulatedType(*type);
    if (!simulated) {
      if (!isLeftOutType(*type)) {
        fail(element, "type '" + *type +
                          "' is not a sensor type servoloop or Gazebo knows; servoloop simulates imu, force_torque "
                          "and contact, and leaves out the other types Gazebo knows (" +
                          leftOutTypeList() + ")");
      }
      logger().warn("{}: a Gazebo {} sensor, which servoloop does not simulate; it is left out", element, *type);
      return;
    }

    SensorDescription sensor;
    sensor.name = name;
    sensor.type = *simulated;
    sensor.reference = reference;
    sensor.element = element;
    if (sensor.type == SensorType::force_torque) {
      const urdf::JointConstSharedPtr joint = model_.getJoint(reference);
      if (!joint) fail(element, "reference='" + reference + "': " + whyNoJoint(reference));
      sensor.frame_id = joint->child_link_name;
    } else {
      if (!model_.getLink(reference)) {
        fail(element, "reference='" + reference + "': " + whyNoLink(reference, sensor.type));
      }
      // gazebo_ros_bumper's frameName defaults to the world frame.
      sensor.frame_id = sensor.type == SensorType::contact ? "world" : reference;
    }

    // Gazebo before 1.0 spelt the common settings in camelCase.
    if (const XMLElement* e = xml.FirstChildElement(legacy ? "alwaysOn" : "always_on")) {
      sensor.always_on = readBool(element, xml, *e);
    }
    const XMLElement* rate = xml.FirstChildElement(legacy ? "updateRate" : "update_rate");
    if (rate != nullptr) sensor.update_rate_hz = readRate(element, xml, *rate);
    if (const XMLElement* e = xml.FirstChildElement("pose")) sensor.pose = readPose(element, xml, *e);

    ImuNoiseGiven imu_noise;
    switch (sensor.type) {
      case SensorType::imu:
        imu_noise = readImuBlock(xml, sensor);
        break;
      case SensorType::force_torque:
        readForceTorqueBlock(xml, sensor);
        break;
      case SensorType::contact:
        readContactBlock(xml, legacy, sensor);
        break;
    }
    readSensorPlugins(xml, rate != nullptr, imu_noise, sensor);
    add(std::move(sensor));
  }

  struct ImuNoiseGiven {
    bool angular_velocity = false;
    bool linear_acceleration = false;
  };

  // <imu><angular_velocity><x><noise type="gaussian">... (SDFormat 1.5 on),
  // or <imu><noise><type>gaussian</type><rate>...</rate><accel>...</accel>
  // (1.4: one noise for all three axes).
  ImuNoiseGiven readImuBlock(const XMLElement& xml, SensorDescription& sensor) const {
    ImuNoiseGiven given;
    const XMLElement* imu = xml.FirstChildElement("imu");
    if (imu == nullptr) return given;
    const std::string& element = sensor.element;
    const auto read_axes = [&](const char* quantity, std::array<GaussianNoise, 3>& noise, bool& was_given) {
      const XMLElement* holder = imu->FirstChildElement(quantity);
      if (holder == nullptr) return;
      constexpr const char* kAxes[] = {"x", "y", "z"};
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const XMLElement* axis_element = holder->FirstChildElement(kAxes[axis]);
        const XMLElement* n = axis_element != nullptr ? axis_element->FirstChildElement("noise") : nullptr;
        if (n == nullptr) continue;
        was_given = true;
        noise[axis] = noiseIsOn(element, xml, *n) ? readNoiseValues(element, xml, *n) : GaussianNoise{};
      }
    };
    read_axes("angular_velocity", sensor.angular_velocity_noise, given.angular_velocity);
    read_axes("linear_acceleration", sensor.linear_acceleration_noise, given.linear_acceleration);

    if (const XMLElement* n = imu->FirstChildElement("noise")) {
      const bool on = noiseIsOn(element, xml, *n);
      const auto read_all_axes = [&](const char* tag, std::array<GaussianNoise, 3>& noise, bool& was_given) {
        const XMLElement* holder = n->FirstChildElement(tag);
        if (holder == nullptr) return;
        was_given = true;
        const GaussianNoise value = on ? readNoiseValues(element, xml, *holder) : GaussianNoise{};
        noise = {value, value, value};
      };
      read_all_axes("rate", sensor.angular_velocity_noise, given.angular_velocity);
      read_all_axes("accel", sensor.linear_acceleration_noise, given.linear_acceleration);
    }
    return given;
  }

  static void readForceTorqueBlock(const XMLElement& xml, SensorDescription& sensor) {
    const XMLElement* ft = xml.FirstChildElement("force_torque");
    if (ft == nullptr) return;
    if (const XMLElement* e = ft->FirstChildElement("frame")) {
      const std::string frame = textOf(*e);
      if (frame == "child") {
        sensor.frame = ForceTorqueFrame::child;
      } else if (frame == "parent") {
        sensor.frame = ForceTorqueFrame::parent;
      } else if (frame == "sensor") {
        sensor.frame = ForceTorqueFrame::sensor;
      } else {
        failValue(sensor.element, xml, *e,
                  "the frame the wrench is given in is child, parent or sensor (the joint's child link, its parent "
                  "link, or the sensor's <pose>); write e.g. <frame>child</frame>");
      }
    }
    if (const XMLElement* e = ft->FirstChildElement("measure_direction")) {
      const std::string direction = textOf(*e);
      if (direction == "child_to_parent") {
        sensor.measure_direction = ForceTorqueDirection::child_to_parent;
      } else if (direction == "parent_to_child") {
        sensor.measure_direction = ForceTorqueDirection::parent_to_child;
      } else {
        failValue(sensor.element, xml, *e,
                  "the direction is child_to_parent (the wrench the child link applies to the parent) or "
                  "parent_to_child; write e.g. <measure_direction>child_to_parent</measure_direction>");
      }
    }
  }

  // <contact><collision>NAME</collision>..., or before Gazebo 1.0
  // <sensor:contact><geom>NAME</geom>.
  void readContactBlock(const XMLElement& xml, bool legacy, SensorDescription& sensor) const {
    std::vector<const XMLElement*> names;
    if (const XMLElement* contact = xml.FirstChildElement("contact")) {
      for (auto* e = contact->FirstChildElement("collision"); e != nullptr; e = e->NextSiblingElement("collision")) {
        names.push_back(e);
      }
    }
    if (legacy) {
      for (auto* e = xml.FirstChildElement("geom"); e != nullptr; e = e->NextSiblingElement("geom")) names.push_back(e);
    }
    const std::string& link = sensor.reference;
    const std::string naming = "Gazebo calls the collisions of link '" + link + "' '" + link + "_collision', '" + link +
                               "_collision_1', ..., those of a link fixed below it '" + link +
                               "_fixed_joint_lump__<that link>_collision' and, when a fixed joint merges '" + link +
                               "' into the link above it, '<that link>_fixed_joint_lump__" + link + "_collision'";
    if (names.empty()) {
      fail(sensor.element, "a contact sensor needs <contact><collision>NAME</collision></contact> naming the "
                           "collision it reports; " + naming + ", e.g. <collision>" + link + "_collision</collision>");
    }
    const urdf::LinkConstSharedPtr model_link = model_.getLink(link);
    for (const XMLElement* e : names) {
      const std::string collision = textOf(*e);
      if (collision.empty()) {
        failValue(sensor.element, xml, *e, "a contact sensor's collision needs a name; " + naming);
      }
      if (!isCollisionOf(collision, *model_link)) {
        failValue(sensor.element, xml, *e, "not a collision of link '" + link + "', the sensor's reference; " + naming);
      }
      sensor.collisions.push_back(collision);
    }
  }

  // The gazebo_ros plugin inside a <sensor>: its topic and frame, its rate
  // when the sensor gives none, and its noise.
  void readSensorPlugins(const XMLElement& xml, bool sensor_has_rate, ImuNoiseGiven imu_noise,
                         SensorDescription& sensor) const {
    for (auto* plugin = xml.FirstChildElement(); plugin != nullptr; plugin = plugin->NextSiblingElement()) {
      const std::string stem = pluginStem(*plugin);
      PluginFields fields{};
      if (sensor.type == SensorType::imu && stem == "gazebo_ros_imu_sensor") {
        fields = {"topicName", "updateRateHZ"};
      } else if (sensor.type == SensorType::force_torque && stem == "gazebo_ros_ft_sensor") {
        fields = {"topicName", "updateRate"};
      } else if (sensor.type == SensorType::contact && stem == "gazebo_ros_bumper") {
        fields = {"bumperTopicName", "updateRate"};
      } else {
        continue;
      }
      const std::string& element = sensor.element;
      if (const XMLElement* e = plugin->FirstChildElement(fields.topic)) sensor.topic = textOf(*e);
      if (const XMLElement* e = plugin->FirstChildElement("frameName"); e != nullptr && !textOf(*e).empty()) {
        sensor.frame_id = textOf(*e);
      }
      if (const XMLElement* e = plugin->FirstChildElement(fields.rate)) {
        const double rate = readRate(element, xml, *e);
        if (!sensor_has_rate) sensor.update_rate_hz = rate;
      }
      const XMLElement* noise_element = plugin->FirstChildElement("gaussianNoise");
      if (noise_element == nullptr || sensor.type == SensorType::contact) continue;
      const double stddev = readStddev(element, xml, *noise_element);
      if (sensor.type == SensorType::force_torque) {
        sensor.wrench_noise.stddev = stddev;
        continue;
      }
      // gazebo_ros_imu_sensor: on every axis of every quantity, where <imu> gave none.
      if (!imu_noise.angular_velocity) setStddev(sensor.angular_velocity_noise, {stddev, stddev, stddev});
      if (!imu_noise.linear_acceleration) setStddev(sensor.linear_acceleration_noise, {stddev, stddev, stddev});
      sensor.orientation_noise.stddev = stddev;
    }
  }

  static void setStddev(std::array<GaussianNoise, 3>& noise, const std::array<double, 3>& stddev) {
    for (std::size_t axis = 0; axis < 3; ++axis) noise[axis].stddev = stddev[axis];
  }

  // ---------------------------------------------------------------------------
  // Model plugins in <gazebo> without reference.

  // "r.urdf: <gazebo><plugin name='imu' filename='libgazebo_ros_imu.so'>".
  std::string pluginElement(const XMLElement& plugin) const {
    const bool modern = std::string_view(plugin.Name()) == "plugin";
    const char* name = plugin.Attribute("name");
    const char* file = plugin.Attribute(modern ? "filename" : "plugin");
    return source_ + ": <gazebo><" + plugin.Name() + (name != nullptr ? std::string(" name='") + name + "'" : "") +
           (modern ? " filename='" : " plugin='") + (file != nullptr ? file : "") + "'>";
  }

  // A model plugin's sensor: named after the plugin, with its common settings.
  SensorDescription pluginSensor(const XMLElement& plugin, SensorType type) const {
    SensorDescription sensor;
    sensor.type = type;
    sensor.element = pluginElement(plugin);
    const char* name = plugin.Attribute("name");
    if (name == nullptr || trim(name).empty()) {
      const std::string example = std::string("<") + plugin.Name() + " name=\"" +
                                  (type == SensorType::imu ? "imu" : "ft") + "_sensor\" ...>";
      fail(sensor.element, "the plugin has no name, which names its sensor; give it one of its own, e.g. " + example);
    }
    sensor.name = name;
    if (const XMLElement* e = plugin.FirstChildElement("alwaysOn")) {
      sensor.always_on = readBool(sensor.element, plugin, *e);
    }
    if (const XMLElement* e = plugin.FirstChildElement("updateRate")) {
      sensor.update_rate_hz = readRate(sensor.element, plugin, *e);
    }
    if (const XMLElement* e = plugin.FirstChildElement("topicName")) sensor.topic = textOf(*e);
    return sensor;
  }

  // The link hector's IMU sits on without <bodyName>: Gazebo's canonical
  // link, the model's first (the root's child when the root is "world",
  // which Gazebo does not create).
  std::string canonicalLink() const {
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) return "";
    if (root->name == "world" && !root->child_links.empty()) return root->child_links.front()->name;
    return root->name;
  }

  // gazebo_ros_imu (also as PR2's <controller:gazebo_ros_imu>) and
  // hector_gazebo_ros_imu.
  void readImuPlugin(const XMLElement& plugin, bool hector) {
    SensorDescription sensor = pluginSensor(plugin, SensorType::imu);
    const std::string& element = sensor.element;
    const XMLElement* body = plugin.FirstChildElement("bodyName");
    if (body == nullptr && !hector) {
      fail(element, "gazebo_ros_imu needs <bodyName>, the link the IMU is on; add e.g. <bodyName>imu_link</bodyName>");
    }
    sensor.reference = body != nullptr ? textOf(*body) : canonicalLink();
    if (!model_.getLink(sensor.reference)) {
      if (body == nullptr) fail(element, "the robot has no link for the IMU; add <bodyName>, the link it is on");
      failValue(element, plugin, *body, whyNoLink(sensor.reference, SensorType::imu));
    }
    sensor.frame_id = sensor.reference;
    for (const char* tag : {"frameName", "frameId"}) {
      if (const XMLElement* e = plugin.FirstChildElement(tag); e != nullptr && !textOf(*e).empty()) {
        sensor.frame_id = textOf(*e);
      }
    }

    // The mounting offset: <xyzOffset> and <rpyOffset>, or the older plurals.
    const auto offset = [&](const char* tag, const char* old_tag) {
      const XMLElement* e = plugin.FirstChildElement(tag);
      return e != nullptr ? e : plugin.FirstChildElement(old_tag);
    };
    if (const XMLElement* e = offset("xyzOffset", "xyzOffsets")) {
      const std::array<double, 3> xyz = readVector3(element, plugin, *e, "x y z (m)");
      std::copy(xyz.begin(), xyz.end(), sensor.pose.begin());
    }
    if (const XMLElement* e = offset("rpyOffset", "rpyOffsets")) {
      const std::array<double, 3> rpy = readVector3(element, plugin, *e, "roll pitch yaw (rad)");
      std::copy(rpy.begin(), rpy.end(), sensor.pose.begin() + 3);
    }

    const XMLElement* gaussian = plugin.FirstChildElement("gaussianNoise");
    const double stddev = gaussian != nullptr ? readStddev(element, plugin, *gaussian) : 0.0;
    if (!hector) {
      // gazebo_ros_imu: on the rates and accelerations, and in the orientation's covariance.
      setStddev(sensor.angular_velocity_noise, {stddev, stddev, stddev});
      setStddev(sensor.linear_acceleration_noise, {stddev, stddev, stddev});
      sensor.orientation_noise.stddev = stddev;
    } else {
      // hector: per axis, with the older <gaussianNoise> (when not 0) in
      // place of both, as hector reads them; its drift and heading models
      // are not simulated.
      if (const XMLElement* e = plugin.FirstChildElement("rateGaussianNoise")) {
        setStddev(sensor.angular_velocity_noise, readStddevPerAxis(element, plugin, *e));
      }
      if (const XMLElement* e = plugin.FirstChildElement("accelGaussianNoise")) {
        setStddev(sensor.linear_acceleration_noise, readStddevPerAxis(element, plugin, *e));
      }
      if (stddev != 0.0) {
        setStddev(sensor.angular_velocity_noise, {stddev, stddev, stddev});
        setStddev(sensor.linear_acceleration_noise, {stddev, stddev, stddev});
      }
    }
    add(std::move(sensor));
  }

  // gazebo_ros_ft_sensor: the wrench of <jointName> in its child link's
  // frame, as the SDFormat defaults (child, child_to_parent) give it.
  void readForceTorquePlugin(const XMLElement& plugin) {
    SensorDescription sensor = pluginSensor(plugin, SensorType::force_torque);
    const std::string& element = sensor.element;
    const XMLElement* joint_element = plugin.FirstChildElement("jointName");
    if (joint_element == nullptr) {
      fail(element, "gazebo_ros_ft_sensor needs <jointName>, the joint it measures; add e.g. "
                    "<jointName>wrist_joint</jointName>");
    }
    sensor.reference = textOf(*joint_element);
    const urdf::JointConstSharedPtr joint = model_.getJoint(sensor.reference);
    if (!joint) failValue(element, plugin, *joint_element, whyNoJoint(sensor.reference));
    sensor.frame_id = joint->child_link_name;
    if (const XMLElement* e = plugin.FirstChildElement("gaussianNoise")) {
      sensor.wrench_noise.stddev = readStddev(element, plugin, *e);
    }
    add(std::move(sensor));
  }

  // ---------------------------------------------------------------------------

  // Sensors are told apart by what their handle is named after: the topic
  // of their gazebo_ros plugin, else their name (as sim_common names the
  // handles). Plugins of one name on topics of their own are distinct, as in
  // Gazebo (Kinova's arms name every joint's ft plugin "ft_sensor").
  void add(SensorDescription sensor) {
    std::string topic = sensor.topic;
    while (!topic.empty() && topic.front() == '/') topic.erase(topic.begin());
    const std::string key = topic.empty() ? sensor.name : topic;
    const auto [first, inserted] = by_name_.emplace(key, sensors_.size());
    if (!inserted) {
      const std::string& other = sensors_[first->second].element;
      const std::string other_place = startsWith(other, source_ + ": ") ? other.substr(source_.size() + 2) : other;
      fail(sensor.element, topic.empty() ? "a second sensor named '" + sensor.name + "' (the first: " + other_place +
                                               "); give each sensor of the robot a name of its own"
                                         : "a second sensor publishing on '" + sensor.topic + "' (the first: " +
                                               other_place + "); give each sensor a topic of its own");
    }
    sensors_.push_back(std::move(sensor));
  }

  const urdf::ModelInterface& model_;
  const std::string& source_;
  std::set<std::string> urdf_links_;   // as the text names them, left out or not
  std::set<std::string> urdf_joints_;
  std::vector<SensorDescription> sensors_;
  std::map<std::string, std::size_t> by_name_;  // handle name -> index into sensors_
};

}  // namespace

const char* toString(SensorType type) noexcept {
  switch (type) {
    case SensorType::imu:
      return "imu";
    case SensorType::force_torque:
      return "force_torque";
    case SensorType::contact:
      return "contact";
  }
  return "?";
}

std::vector<SensorDescription> readGazeboSensors(const std::string& urdf_xml, const urdf::ModelInterface& model,
                                                 const std::string& source_name) {
  tinyxml2::XMLDocument document;
  // (The model was parsed from this text, so it is XML with a <robot> root.)
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) return {};
  const XMLElement* robot = document.RootElement();
  if (robot == nullptr) return {};
  SensorReader reader(*robot, model, source_name);
  for (auto* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    const char* reference = gazebo->Attribute("reference");
    if (reference != nullptr) {
      reader.readReferenced(*gazebo, reference);
    } else {
      reader.readModelPlugins(*gazebo);
    }
  }
  return reader.take();
}

}  // namespace servoloop
