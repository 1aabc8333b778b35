#pragma once
// A contact sensor (Gazebo's <sensor type="contact">, read by
// gazebo_ros_bumper): the contact points of one link's collision geometry
// with anything else in the world during the last step, in world
// coordinates. ros_control has no such interface; simulated hardware offers
// it so the node can publish gazebo_msgs/ContactsState as the bumper plugin
// does, and a controller may read it. Reading is real-time safe.
#include <array>
#include <cstddef>
#include <string>

#include "servoloop/hardware_interface/resource_manager.hpp"

namespace servoloop::hardware_interface {

struct ContactPoint {
  // The other collision, Gazebo's scoped name "model::link::collision"
  // (NUL-terminated, cut at the array's length).
  std::array<char, 128> other_collision{};
  double position[3] = {0.0, 0.0, 0.0};  // m, world frame
  double normal[3] = {0.0, 0.0, 1.0};    // unit, world axes: the normal force's direction on the sensor's link
  double force[3] = {0.0, 0.0, 0.0};     // N, world axes: what the other body applies to the sensor's link
  double depth = 0.0;                    // m, how far the two overlap (0 when they just touch)
};

struct ContactSensorReading {
  static constexpr std::size_t kCapacity = 64;
  std::size_t count = 0;    // points in `points`
  std::size_t dropped = 0;  // points of the last sample beyond kCapacity, left out
  double link_position[3] = {0.0, 0.0, 0.0};  // the sensor link frame's origin, world frame (torques are about it)
  std::array<ContactPoint, kCapacity> points{};
};

class ContactSensorHandle {
 public:
  struct Data {
    std::string name;            // the sensor's name
    std::string frame_id;        // header.frame_id of its messages (gazebo_ros_bumper's frameName; "world")
    std::string collision;       // the sensor link's collision, scoped: "model::link::collision"
    std::string topic;           // gazebo_ros_bumper's topic, relative to the robot's namespace
    double update_rate_hz = 0;   // 0: every step
    const ContactSensorReading* reading = nullptr;
  };

  ContactSensorHandle() = default;
  // Throws servoloop::Error for an empty name or a null reading.
  explicit ContactSensorHandle(const Data& data);

  const std::string& getName() const { return data_.name; }
  const std::string& getFrameId() const { return data_.frame_id; }
  const std::string& getCollision() const { return data_.collision; }
  const std::string& getTopic() const { return data_.topic; }
  double getUpdateRate() const { return data_.update_rate_hz; }
  const ContactSensorReading& getReading() const { return *data_.reading; }

 private:
  Data data_;
};

extern template class ResourceManager<ContactSensorHandle, false>;

// Read-only: claims nothing.
class ContactSensorInterface : public ResourceManager<ContactSensorHandle, false> {
 public:
  const char* name() const override;
};

}  // namespace servoloop::hardware_interface
