// Each message type's JSON form, both ways (message_json.hpp).
#include <array>
#include <string>

#include "message_json_detail.hpp"
#include "servoloop/node/message_json.hpp"

namespace servoloop::node {

using nlohmann::json;
using namespace detail;

// --- JSON per type ------------------------------------------------------------------

json toJson(const std_msgs::Float64& msg) { return json{{"data", msg.data}}; }

json toJson(const std_msgs::Float64MultiArray& msg) { return json{{"data", numberList(msg.data)}}; }
json toJson(const std_msgs::Bool& msg) { return json{{"data", msg.data}}; }

json toJson(const diagnostic_msgs::DiagnosticArray& msg) {
  json status = json::array();
  for (const auto& s : msg.status) {
    json values = json::array();
    for (const auto& kv : s.values) values.push_back({{"key", kv.key}, {"value", kv.value}});
    status.push_back({{"level", s.level},
                      {"name", s.name},
                      {"message", s.message},
                      {"hardware_id", s.hardware_id},
                      {"values", std::move(values)}});
  }
  return json{{"stamp", msg.stamp}, {"status", std::move(status)}};
}

json toJson(const sensor_msgs::JointState& msg) {
  return json{{"stamp", msg.stamp},
              {"name", msg.name},
              {"position", numberList(msg.position)},
              {"velocity", numberList(msg.velocity)},
              {"effort", numberList(msg.effort)}};
}

json toJson(const control_msgs::JointControllerState& msg) {
  return json{{"stamp", msg.stamp},         {"set_point", msg.set_point},
              {"process_value", msg.process_value}, {"process_value_dot", msg.process_value_dot},
              {"error", msg.error},         {"time_step", msg.time_step},
              {"command", msg.command},     {"p", msg.p},
              {"i", msg.i},                 {"d", msg.d},
              {"i_clamp", msg.i_clamp},     {"antiwindup", msg.antiwindup}};
}

json toJson(const nav_msgs::Odometry& msg) {
  return json{{"stamp", msg.stamp},
              {"frame_id", msg.frame_id},
              {"child_frame_id", msg.child_frame_id},
              {"pose",
               {{"position", {{"x", msg.position.x}, {"y", msg.position.y}, {"z", msg.position.z}}},
                {"orientation",
                 {{"x", msg.orientation.x}, {"y", msg.orientation.y}, {"z", msg.orientation.z},
                  {"w", msg.orientation.w}}},
                {"covariance", numberList({msg.pose_covariance.begin(), msg.pose_covariance.end()})}}},
              {"twist",
               {{"linear", {{"x", msg.linear.x}, {"y", msg.linear.y}, {"z", msg.linear.z}}},
                {"angular", {{"x", msg.angular.x}, {"y", msg.angular.y}, {"z", msg.angular.z}}},
                {"covariance", numberList({msg.twist_covariance.begin(), msg.twist_covariance.end()})}}}};
}

json toJson(const geometry_msgs::Twist& msg) {
  return json{{"linear", {{"x", msg.linear.x}, {"y", msg.linear.y}, {"z", msg.linear.z}}},
              {"angular", {{"x", msg.angular.x}, {"y", msg.angular.y}, {"z", msg.angular.z}}}};
}

json toJson(const tf2_msgs::TFMessage& msg) {
  json transforms = json::array();
  for (const auto& t : msg.transforms) {
    transforms.push_back(
        {{"stamp", t.stamp},
         {"frame_id", t.frame_id},
         {"child_frame_id", t.child_frame_id},
         {"translation", {{"x", t.translation.x}, {"y", t.translation.y}, {"z", t.translation.z}}},
         {"rotation", {{"x", t.rotation.x}, {"y", t.rotation.y}, {"z", t.rotation.z}, {"w", t.rotation.w}}}});
  }
  return json{{"transforms", transforms}};
}

json toJson(const gazebo_msgs::ModelStates& msg) {
  json poses = json::array();
  json twists = json::array();
  for (const geometry_msgs::Pose& p : msg.pose) {
    poses.push_back({{"position", {{"x", p.position.x}, {"y", p.position.y}, {"z", p.position.z}}},
                     {"orientation",
                      {{"x", p.orientation.x}, {"y", p.orientation.y}, {"z", p.orientation.z},
                       {"w", p.orientation.w}}}});
  }
  for (const geometry_msgs::Twist& t : msg.twist) twists.push_back(toJson(t));
  return json{{"name", msg.name}, {"pose", poses}, {"twist", twists}};
}

namespace {

json vector3Json(const geometry_msgs::Vector3& v) { return json{{"x", v.x}, {"y", v.y}, {"z", v.z}}; }

json wrenchJson(const geometry_msgs::Wrench& w) {
  return json{{"force", vector3Json(w.force)}, {"torque", vector3Json(w.torque)}};
}

json covarianceJson(const std::array<double, 9>& covariance) {
  return numberList({covariance.begin(), covariance.end()});
}

}  // namespace

json toJson(const geometry_msgs::WrenchStamped& msg) {
  return json{{"stamp", msg.stamp}, {"frame_id", msg.frame_id}, {"wrench", wrenchJson(msg.wrench)}};
}

json toJson(const sensor_msgs::Imu& msg) {
  const geometry_msgs::Quaternion& q = msg.orientation;
  return json{{"stamp", msg.stamp},
              {"frame_id", msg.frame_id},
              {"orientation", {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}},
              {"orientation_covariance", covarianceJson(msg.orientation_covariance)},
              {"angular_velocity", vector3Json(msg.angular_velocity)},
              {"angular_velocity_covariance", covarianceJson(msg.angular_velocity_covariance)},
              {"linear_acceleration", vector3Json(msg.linear_acceleration)},
              {"linear_acceleration_covariance", covarianceJson(msg.linear_acceleration_covariance)}};
}

json toJson(const gazebo_msgs::ContactsState& msg) {
  json states = json::array();
  for (const gazebo_msgs::ContactState& c : msg.states) {
    json wrenches = json::array();
    for (const geometry_msgs::Wrench& w : c.wrenches) wrenches.push_back(wrenchJson(w));
    json positions = json::array();
    for (const geometry_msgs::Vector3& p : c.contact_positions) positions.push_back(vector3Json(p));
    json normals = json::array();
    for (const geometry_msgs::Vector3& n : c.contact_normals) normals.push_back(vector3Json(n));
    states.push_back({{"info", c.info},
                      {"collision1_name", c.collision1_name},
                      {"collision2_name", c.collision2_name},
                      {"wrenches", std::move(wrenches)},
                      {"total_wrench", wrenchJson(c.total_wrench)},
                      {"contact_positions", std::move(positions)},
                      {"contact_normals", std::move(normals)},
                      {"depths", numberList(c.depths)}});
  }
  return json{{"stamp", msg.stamp}, {"frame_id", msg.frame_id}, {"states", std::move(states)}};
}

namespace {

json toJson(const trajectory_msgs::JointTrajectoryPoint& point) {
  return json{{"positions", numberList(point.positions)},
              {"velocities", numberList(point.velocities)},
              {"accelerations", numberList(point.accelerations)},
              {"effort", numberList(point.effort)},
              {"time_from_start", point.time_from_start}};
}

void pointFromJson(std::string_view type_name, const json& value, const std::string& where,
                   trajectory_msgs::JointTrajectoryPoint& out) {
  FieldReader reader(type_name, value, pointFields(), where);
  reader.numbers("positions", out.positions);
  reader.numbers("velocities", out.velocities);
  reader.numbers("accelerations", out.accelerations);
  reader.numbers("effort", out.effort);
  reader.number("time_from_start", out.time_from_start);
}

}  // namespace

json toJson(const trajectory_msgs::JointTrajectory& msg) {
  json points = json::array();
  for (const auto& point : msg.points) points.push_back(toJson(point));
  return json{{"stamp", msg.stamp}, {"joint_names", msg.joint_names}, {"points", points}};
}

json toJson(const control_msgs::JointTrajectoryControllerState& msg) {
  return json{{"stamp", msg.stamp},
              {"joint_names", msg.joint_names},
              {"desired", toJson(msg.desired)},
              {"actual", toJson(msg.actual)},
              {"error", toJson(msg.error)}};
}

void fromJson(const json& value, std_msgs::Float64& out) {
  if (value.is_number()) {  // `topic pub /cmd std_msgs/Float64 1.0`
    out.data = value.get<double>();
    return;
  }
  FieldReader reader(std_msgs::Float64::kTypeName, value);
  reader.number("data", out.data);
}

void fromJson(const json& value, diagnostic_msgs::DiagnosticArray& out) {
  constexpr std::string_view type = diagnostic_msgs::DiagnosticArray::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  const json* status = reader.field("status");
  if (status == nullptr) return;
  if (!status->is_array()) reader.fail("status", "a list of statuses", *status);
  static const std::vector<std::string_view> fields = {"level", "name", "message", "hardware_id", "values"};
  static const std::vector<std::string_view> key_value = {"key", "value"};
  out.status.assign(status->size(), {});
  for (std::size_t i = 0; i < status->size(); ++i) {
    const std::string where = "status[" + std::to_string(i) + "]";
    FieldReader item(type, (*status)[i], fields, where);
    auto& s = out.status[i];
    double level = 0.0;
    item.number("level", level);
    if (level != 0.0 && level != 1.0 && level != 2.0 && level != 3.0) {
      item.fail("level", "0 (OK), 1 (WARN), 2 (ERROR) or 3 (STALE)", (*status)[i]["level"]);
    }
    s.level = static_cast<int>(level);
    item.text("name", s.name);
    item.text("message", s.message);
    item.text("hardware_id", s.hardware_id);
    const json* values = item.field("values");
    if (values == nullptr) continue;
    if (!values->is_array()) item.fail("values", "a list of {key, value}", *values);
    for (std::size_t k = 0; k < values->size(); ++k) {
      FieldReader pair(type, (*values)[k], key_value, where + ".values[" + std::to_string(k) + "]");
      diagnostic_msgs::KeyValue kv;
      pair.text("key", kv.key);
      pair.text("value", kv.value);
      s.values.push_back(std::move(kv));
    }
  }
}

void fromJson(const json& value, std_msgs::Bool& out) {
  if (value.is_boolean()) {  // `topic pub /estop std_msgs/Bool true`
    out.data = value.get<bool>();
    return;
  }
  FieldReader reader(std_msgs::Bool::kTypeName, value);
  reader.boolean("data", out.data);
}

void fromJson(const json& value, std_msgs::Float64MultiArray& out) {
  if (value.is_array()) {  // `topic pub /cmd std_msgs/Float64MultiArray "[1, 2]"`
    FieldReader(std_msgs::Float64MultiArray::kTypeName, json{{"data", value}}).numbers("data", out.data);
    return;
  }
  FieldReader reader(std_msgs::Float64MultiArray::kTypeName, value);
  reader.numbers("data", out.data);
}

void fromJson(const json& value, sensor_msgs::JointState& out) {
  FieldReader reader(sensor_msgs::JointState::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.strings("name", out.name);
  reader.numbers("position", out.position);
  reader.numbers("velocity", out.velocity);
  reader.numbers("effort", out.effort);
  const auto check_size = [&](const char* field, const std::vector<double>& values) {
    if (!values.empty() && values.size() != out.name.size()) {
      throw Error(std::string(sensor_msgs::JointState::kTypeName) + ": field '" + field + "' has " +
                  std::to_string(values.size()) + " entries but 'name' has " + std::to_string(out.name.size()) +
                  "; give one per joint or none");
    }
  };
  check_size("position", out.position);
  check_size("velocity", out.velocity);
  check_size("effort", out.effort);
}

void fromJson(const json& value, control_msgs::JointControllerState& out) {
  FieldReader reader(control_msgs::JointControllerState::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.number("set_point", out.set_point);
  reader.number("process_value", out.process_value);
  reader.number("process_value_dot", out.process_value_dot);
  reader.number("error", out.error);
  reader.number("time_step", out.time_step);
  reader.number("command", out.command);
  reader.number("p", out.p);
  reader.number("i", out.i);
  reader.number("d", out.d);
  reader.number("i_clamp", out.i_clamp);
  reader.boolean("antiwindup", out.antiwindup);
}

void fromJson(const json& value, nav_msgs::Odometry& out) {
  FieldReader reader(nav_msgs::Odometry::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.text("frame_id", out.frame_id);
  reader.text("child_frame_id", out.child_frame_id);
  const json* pose = reader.field("pose");
  reader.numberObject("pose.position",
                      reader.child("pose", pose, "position", {"position", "orientation", "covariance"}),
                      {"x", "y", "z"}, {&out.position.x, &out.position.y, &out.position.z});
  reader.numberObject("pose.orientation",
                      reader.child("pose", pose, "orientation", {"position", "orientation", "covariance"}),
                      {"x", "y", "z", "w"},
                      {&out.orientation.x, &out.orientation.y, &out.orientation.z, &out.orientation.w});
  reader.fixedNumbers("pose.covariance", reader.child("pose", pose, "covariance", {"position", "orientation", "covariance"}),
                      out.pose_covariance.data(), out.pose_covariance.size());
  const json* twist = reader.field("twist");
  reader.numberObject("twist.linear", reader.child("twist", twist, "linear", {"linear", "angular", "covariance"}),
                      {"x", "y", "z"}, {&out.linear.x, &out.linear.y, &out.linear.z});
  reader.numberObject("twist.angular", reader.child("twist", twist, "angular", {"linear", "angular", "covariance"}),
                      {"x", "y", "z"}, {&out.angular.x, &out.angular.y, &out.angular.z});
  reader.fixedNumbers("twist.covariance", reader.child("twist", twist, "covariance", {"linear", "angular", "covariance"}),
                      out.twist_covariance.data(), out.twist_covariance.size());
}

void fromJson(const json& value, geometry_msgs::Twist& out) {
  FieldReader reader(geometry_msgs::Twist::kTypeName, value);
  reader.numberObject("linear", reader.field("linear"), {"x", "y", "z"}, {&out.linear.x, &out.linear.y, &out.linear.z});
  reader.numberObject("angular", reader.field("angular"), {"x", "y", "z"},
                      {&out.angular.x, &out.angular.y, &out.angular.z});
}

void fromJson(const json& value, tf2_msgs::TFMessage& out) {
  constexpr std::string_view type = tf2_msgs::TFMessage::kTypeName;
  FieldReader reader(type, value);
  const json* transforms = reader.field("transforms");
  if (transforms == nullptr) return;
  if (!transforms->is_array()) reader.fail("transforms", "a list of transforms", *transforms);
  static const std::vector<std::string_view> fields = {"stamp", "frame_id", "child_frame_id", "translation",
                                                       "rotation"};
  out.transforms.assign(transforms->size(), {});
  for (std::size_t i = 0; i < transforms->size(); ++i) {
    const std::string where = "transforms[" + std::to_string(i) + "]";
    FieldReader item(type, (*transforms)[i], fields, where);
    auto& t = out.transforms[i];
    item.number("stamp", t.stamp);
    item.text("frame_id", t.frame_id);
    item.text("child_frame_id", t.child_frame_id);
    item.numberObject("translation", item.field("translation"), {"x", "y", "z"},
                      {&t.translation.x, &t.translation.y, &t.translation.z});
    item.numberObject("rotation", item.field("rotation"), {"x", "y", "z", "w"},
                      {&t.rotation.x, &t.rotation.y, &t.rotation.z, &t.rotation.w});
  }
}

void fromJson(const json& value, gazebo_msgs::ModelStates& out) {
  constexpr std::string_view type = gazebo_msgs::ModelStates::kTypeName;
  FieldReader reader(type, value);
  reader.strings("name", out.name);
  const json* poses = reader.field("pose");
  const json* twists = reader.field("twist");
  if (poses != nullptr && !poses->is_array()) reader.fail("pose", "a list of poses", *poses);
  if (twists != nullptr && !twists->is_array()) reader.fail("twist", "a list of twists", *twists);
  static const std::vector<std::string_view> pose_fields = {"position", "orientation"};
  static const std::vector<std::string_view> twist_fields = {"linear", "angular"};
  out.pose.assign(poses == nullptr ? 0 : poses->size(), {});
  out.twist.assign(twists == nullptr ? 0 : twists->size(), {});
  for (std::size_t i = 0; i < out.pose.size(); ++i) {
    const std::string where = "pose[" + std::to_string(i) + "]";
    FieldReader item(type, (*poses)[i], pose_fields, where);
    geometry_msgs::Pose& p = out.pose[i];
    item.numberObject("position", item.field("position"), {"x", "y", "z"},
                      {&p.position.x, &p.position.y, &p.position.z});
    item.numberObject("orientation", item.field("orientation"), {"x", "y", "z", "w"},
                      {&p.orientation.x, &p.orientation.y, &p.orientation.z, &p.orientation.w});
  }
  for (std::size_t i = 0; i < out.twist.size(); ++i) {
    const std::string where = "twist[" + std::to_string(i) + "]";
    FieldReader item(type, (*twists)[i], twist_fields, where);
    geometry_msgs::Twist& t = out.twist[i];
    item.numberObject("linear", item.field("linear"), {"x", "y", "z"}, {&t.linear.x, &t.linear.y, &t.linear.z});
    item.numberObject("angular", item.field("angular"), {"x", "y", "z"}, {&t.angular.x, &t.angular.y, &t.angular.z});
  }
  if (out.pose.size() != out.name.size() || out.twist.size() != out.name.size()) {
    throw Error(std::string(type) + ": " + std::to_string(out.name.size()) + " names, " +
                std::to_string(out.pose.size()) + " poses and " + std::to_string(out.twist.size()) +
                " twists; give one pose and one twist per name");
  }
}

namespace {

// A geometry_msgs/Wrench {force, torque} nested in a message of `type`; where
// names it in errors ("states[0].total_wrench").
void wrenchFromJson(std::string_view type, const json& value, const std::string& where, geometry_msgs::Wrench& out) {
  static const std::vector<std::string_view> fields = {"force", "torque"};
  FieldReader reader(type, value, fields, where);
  reader.numberObject("force", reader.field("force"), {"x", "y", "z"}, {&out.force.x, &out.force.y, &out.force.z});
  reader.numberObject("torque", reader.field("torque"), {"x", "y", "z"},
                      {&out.torque.x, &out.torque.y, &out.torque.z});
}

// A list of geometry_msgs/Vector3 {x, y, z}, field `field` of reader's object.
void vector3ListFromJson(const FieldReader& reader, const char* field, std::vector<geometry_msgs::Vector3>& out) {
  const json* list = reader.field(field);
  if (list == nullptr) return;
  if (!list->is_array()) reader.fail(field, "a list of {x, y, z}", *list);
  out.assign(list->size(), {});
  for (std::size_t i = 0; i < list->size(); ++i) {
    reader.numberObject(std::string(field) + "[" + std::to_string(i) + "]", &(*list)[i], {"x", "y", "z"},
                        {&out[i].x, &out[i].y, &out[i].z});
  }
}

}  // namespace

void fromJson(const json& value, geometry_msgs::WrenchStamped& out) {
  constexpr std::string_view type = geometry_msgs::WrenchStamped::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.text("frame_id", out.frame_id);
  if (const json* wrench = reader.field("wrench")) wrenchFromJson(type, *wrench, "wrench", out.wrench);
}

void fromJson(const json& value, sensor_msgs::Imu& out) {
  FieldReader reader(sensor_msgs::Imu::kTypeName, value);
  reader.number("stamp", out.stamp);
  reader.text("frame_id", out.frame_id);
  geometry_msgs::Quaternion& q = out.orientation;
  reader.numberObject("orientation", reader.field("orientation"), {"x", "y", "z", "w"}, {&q.x, &q.y, &q.z, &q.w});
  reader.fixedNumbers("orientation_covariance", reader.field("orientation_covariance"),
                      out.orientation_covariance.data(), out.orientation_covariance.size());
  geometry_msgs::Vector3& w = out.angular_velocity;
  reader.numberObject("angular_velocity", reader.field("angular_velocity"), {"x", "y", "z"}, {&w.x, &w.y, &w.z});
  reader.fixedNumbers("angular_velocity_covariance", reader.field("angular_velocity_covariance"),
                      out.angular_velocity_covariance.data(), out.angular_velocity_covariance.size());
  geometry_msgs::Vector3& a = out.linear_acceleration;
  reader.numberObject("linear_acceleration", reader.field("linear_acceleration"), {"x", "y", "z"},
                      {&a.x, &a.y, &a.z});
  reader.fixedNumbers("linear_acceleration_covariance", reader.field("linear_acceleration_covariance"),
                      out.linear_acceleration_covariance.data(), out.linear_acceleration_covariance.size());
}

void fromJson(const json& value, gazebo_msgs::ContactsState& out) {
  constexpr std::string_view type = gazebo_msgs::ContactsState::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.text("frame_id", out.frame_id);
  const json* states = reader.field("states");
  if (states == nullptr) return;
  if (!states->is_array()) reader.fail("states", "a list of contact states", *states);
  static const std::vector<std::string_view> fields = {"info", "collision1_name", "collision2_name", "wrenches",
                                                       "total_wrench", "contact_positions", "contact_normals",
                                                       "depths"};
  out.states.assign(states->size(), {});
  for (std::size_t i = 0; i < states->size(); ++i) {
    const std::string where = "states[" + std::to_string(i) + "]";
    FieldReader item(type, (*states)[i], fields, where);
    gazebo_msgs::ContactState& c = out.states[i];
    item.text("info", c.info);
    item.text("collision1_name", c.collision1_name);
    item.text("collision2_name", c.collision2_name);
    if (const json* wrenches = item.field("wrenches")) {
      if (!wrenches->is_array()) item.fail("wrenches", "a list of {force, torque}", *wrenches);
      c.wrenches.assign(wrenches->size(), {});
      for (std::size_t k = 0; k < wrenches->size(); ++k) {
        wrenchFromJson(type, (*wrenches)[k], where + ".wrenches[" + std::to_string(k) + "]", c.wrenches[k]);
      }
    }
    if (const json* total = item.field("total_wrench")) {
      wrenchFromJson(type, *total, where + ".total_wrench", c.total_wrench);
    }
    vector3ListFromJson(item, "contact_positions", c.contact_positions);
    vector3ListFromJson(item, "contact_normals", c.contact_normals);
    item.numbers("depths", c.depths);
    // Gazebo gives each contact point a wrench, a position, a normal and a depth.
    const std::size_t points = c.contact_positions.size();
    if (c.wrenches.size() != points || c.contact_normals.size() != points || c.depths.size() != points) {
      throw Error(std::string(type) + ": " + where + ": " + std::to_string(c.wrenches.size()) + " wrenches, " +
                  std::to_string(points) + " contact_positions, " + std::to_string(c.contact_normals.size()) +
                  " contact_normals and " + std::to_string(c.depths.size()) +
                  " depths; give one of each per contact point");
    }
  }
}

void fromJson(const json& value, trajectory_msgs::JointTrajectory& out) {
  constexpr std::string_view type = trajectory_msgs::JointTrajectory::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.strings("joint_names", out.joint_names);
  if (const json* points = reader.field("points")) {
    if (!points->is_array()) reader.fail("points", "a list of points", *points);
    out.points.assign(points->size(), {});
    for (std::size_t i = 0; i < points->size(); ++i) {
      pointFromJson(type, (*points)[i], "points[" + std::to_string(i) + "]", out.points[i]);
    }
  }
}

void fromJson(const json& value, control_msgs::JointTrajectoryControllerState& out) {
  constexpr std::string_view type = control_msgs::JointTrajectoryControllerState::kTypeName;
  FieldReader reader(type, value);
  reader.number("stamp", out.stamp);
  reader.strings("joint_names", out.joint_names);
  if (const json* desired = reader.field("desired")) pointFromJson(type, *desired, "desired", out.desired);
  if (const json* actual = reader.field("actual")) pointFromJson(type, *actual, "actual", out.actual);
  if (const json* error = reader.field("error")) pointFromJson(type, *error, "error", out.error);
}

}  // namespace servoloop::node
