#include "gazebo_model_services.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <gazebo_msgs/DeleteModel.h>
#include <gazebo_msgs/GetModelState.h>
#include <gazebo_msgs/SetModelState.h>
#include <gazebo_msgs/SpawnModel.h>
#include <ros/ros.h>

#include "ros_message_json.hpp"

namespace servoloop::ros1 {

using nlohmann::json;

bool isWorldFrame(const std::string& frame) {
  return frame.empty() || frame == "world" || frame == "map" || frame == "/map";
}

std::array<double, 3> rollPitchYaw(double x, double y, double z, double w) {
  const double norm = std::sqrt(x * x + y * y + z * z + w * w);
  if (!std::isfinite(norm)) {
    // Not a rotation: NaN angles, which the node refuses naming them.
    const double not_a_number = std::numeric_limits<double>::quiet_NaN();
    return {not_a_number, not_a_number, not_a_number};
  }
  if (norm == 0.0) return {0.0, 0.0, 0.0};  // the zero quaternion: no rotation
  x /= norm;
  y /= norm;
  z /= norm;
  w /= norm;
  // R = Rz(yaw)·Ry(pitch)·Rx(roll); sin(pitch) is clamped against rounding
  // at the gimbal lock (pitch ±π/2).
  const double roll = std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
  const double pitch = std::asin(std::clamp(2.0 * (w * y - z * x), -1.0, 1.0));
  const double yaw = std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
  return {roll, pitch, yaw};
}

namespace {

// A spawn builds the robot and starts its loop; a delete stops its
// controllers first; both wait for the world to stand between two cycles
// (as `servoloop spawn-model` and `servoloop model delete` wait).
constexpr double kSpawnTimeoutS = 60.0;
constexpr double kDeleteTimeoutS = 30.0;

// The answer to a reference frame other than the world's.
std::string worldFrameOnly(const char* service, const char* field, const std::string& frame) {
  return std::string(service) + ": " + field + " [" + frame +
         "] is not served: servoloop takes poses and twists in the world frame only (give \"\", \"world\" or "
         "\"map\")";
}

// A URDF text in a file of its own under the temporary folder, readable by
// this user only (mkstemps creates it 0600), for model.spawn, which reads a
// file; removed when this goes out of scope.
class TemporaryUrdf {
 public:
  explicit TemporaryUrdf(const std::string& text) {
    const std::filesystem::path folder = std::filesystem::absolute(std::filesystem::temp_directory_path());
    std::string pattern = (folder / "servoloop_spawn_XXXXXX.urdf").string();
    const int fd = ::mkstemps(pattern.data(), 5);  // 5: the ".urdf" that follows the Xs
    if (fd < 0) {
      throw std::runtime_error("cannot create a temporary URDF file in " + folder.string() + ": " +
                               std::strerror(errno));
    }
    path_ = pattern;
    std::size_t written = 0;
    while (written < text.size()) {
      const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int error = errno;
        ::close(fd);
        ::unlink(path_.c_str());
        throw std::runtime_error("cannot write the temporary URDF file " + path_ + ": " + std::strerror(error));
      }
      written += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) {
      const int error = errno;
      ::unlink(path_.c_str());
      throw std::runtime_error("cannot write the temporary URDF file " + path_ + ": " + std::strerror(error));
    }
  }
  ~TemporaryUrdf() { ::unlink(path_.c_str()); }
  TemporaryUrdf(const TemporaryUrdf&) = delete;
  TemporaryUrdf& operator=(const TemporaryUrdf&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

GazeboModelServices::GazeboModelServices(ros::NodeHandle& nh, NodeLink& link, const RobotStateCache& state)
    : link_(link), state_(state) {
  servers_.push_back(nh.advertiseService<gazebo_msgs::GetModelState::Request, gazebo_msgs::GetModelState::Response>(
      "/gazebo/get_model_state",
      [this](gazebo_msgs::GetModelState::Request& request, gazebo_msgs::GetModelState::Response& response) {
        try {
          // World frame and axes: a floating base's ground truth, exact on a
          // paused world; a fixed base's spawn pose, at rest.
          const json model = link_.call("model.get", {{"model", request.model_name}});
          fromJson(model.at("pose"), response.pose);
          fromJson(model.at("twist"), response.twist);
          response.header.stamp = ros::Time(std::max(state_.simTime(), 0.0));
          response.header.frame_id = request.relative_entity_name;
          response.success = true;
          response.status_message = "GetModelState: got properties";
        } catch (const std::exception& e) {
          response.success = false;
          response.status_message = std::string("GetModelState: ") + e.what();
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<gazebo_msgs::SetModelState::Request, gazebo_msgs::SetModelState::Response>(
      "/gazebo/set_model_state",
      [this](gazebo_msgs::SetModelState::Request& request, gazebo_msgs::SetModelState::Response& response) {
        const gazebo_msgs::ModelState& target = request.model_state;
        if (!isWorldFrame(target.reference_frame)) {
          response.success = false;
          response.status_message = worldFrameOnly("SetModelState", "reference_frame", target.reference_frame);
          return true;
        }
        geometry_msgs::Pose pose = target.pose;
        // Gazebo normalises the orientation, and the zero quaternion to the
        // identity: a call that gives only a position (ROS fills the rest
        // with zeros) sets the model upright. The node refuses a zero
        // quaternion, so it is mended here.
        geometry_msgs::Quaternion& q = pose.orientation;
        if (q.x == 0.0 && q.y == 0.0 && q.z == 0.0 && q.w == 0.0) q.w = 1.0;
        try {
          // Both, as Gazebo sets both: a twist left at zero stops the model.
          link_.call("model.set_state",
                     {{"model", target.model_name}, {"pose", toJson(pose)}, {"twist", toJson(target.twist)}});
          response.success = true;
          response.status_message = "SetModelState: set model state done";
        } catch (const std::exception& e) {
          response.success = false;
          response.status_message = std::string("SetModelState: ") + e.what();
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<gazebo_msgs::SpawnModel::Request, gazebo_msgs::SpawnModel::Response>(
      "/gazebo/spawn_urdf_model",
      [this](gazebo_msgs::SpawnModel::Request& request, gazebo_msgs::SpawnModel::Response& response) {
        response.success = false;
        if (request.model_xml.empty()) {
          response.status_message =
              "SpawnModel: Failure - model_xml is empty: give the URDF's text (spawn_model -urdf -param "
              "robot_description reads it from the parameter server, -file from a file)";
          return true;
        }
        if (request.model_xml.find("<robot") == std::string::npos) {
          response.status_message =
              "SpawnModel: Failure - model_xml has no <robot> element: servoloop spawns URDF only (no SDF)";
          return true;
        }
        if (!isWorldFrame(request.reference_frame)) {
          response.status_message = worldFrameOnly("SpawnModel", "reference_frame", request.reference_frame);
          return true;
        }
        const geometry_msgs::Pose& initial = request.initial_pose;
        const geometry_msgs::Quaternion& q = initial.orientation;
        const auto [roll, pitch, yaw] = rollPitchYaw(q.x, q.y, q.z, q.w);
        // toJson of a double writes NaN as null, which the node refuses
        // naming the pose's element.
        json spawn = {{"pose", json::array()}};
        for (const double value : {initial.position.x, initial.position.y, initial.position.z, roll, pitch, yaw}) {
          spawn["pose"].push_back(std::isfinite(value) ? json(value) : json(nullptr));
        }
        if (!request.model_name.empty()) spawn["model"] = request.model_name;
        // spawn_model passes its own ROS namespace, "/" when run at the root:
        // Gazebo's "no namespace". servoloop gives every robot a namespace of
        // its own, /<model> when none is asked for.
        if (!request.robot_namespace.empty() && request.robot_namespace != "/") {
          spawn["namespace"] = request.robot_namespace;
        }
        try {
          const TemporaryUrdf urdf(request.model_xml);
          spawn["urdf"] = urdf.path();
          const json reply = link_.call("model.spawn", spawn, kSpawnTimeoutS);
          std::string warnings;
          for (const json& warning : reply.value("warnings", json::array())) {
            const std::string text = warning.is_string() ? warning.get<std::string>() : warning.dump();
            ROS_WARN("/gazebo/spawn_urdf_model %s: %s", request.model_name.c_str(), text.c_str());
            warnings += (warnings.empty() ? "" : "; ") + text;
          }
          response.success = true;
          response.status_message = "SpawnModel: Successfully spawned entity in namespace " +
                                    reply.value("namespace", std::string("?")) +
                                    (warnings.empty() ? "" : " (warnings: " + warnings + ")");
        } catch (const std::exception& e) {
          response.status_message = std::string("SpawnModel: Failure - ") + e.what();
        }
        return true;
      }));

  servers_.push_back(nh.advertiseService<gazebo_msgs::DeleteModel::Request, gazebo_msgs::DeleteModel::Response>(
      "/gazebo/delete_model",
      [this](gazebo_msgs::DeleteModel::Request& request, gazebo_msgs::DeleteModel::Response& response) {
        try {
          link_.call("model.delete", {{"model", request.model_name}}, kDeleteTimeoutS);
          response.success = true;
          response.status_message = "DeleteModel: successfully deleted model";
        } catch (const std::exception& e) {
          response.success = false;
          response.status_message = std::string("DeleteModel: ") + e.what();
        }
        return true;
      }));
}

}  // namespace servoloop::ros1
