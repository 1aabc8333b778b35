#include "servoloop/sim_common/simulated_sensors.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "servoloop/core/errors.hpp"

namespace servoloop::sim_common {
namespace hi = hardware_interface;
namespace {

// FNV-1a: the same seed for a sensor name in every run and build.
std::uint64_t seedOf(std::string_view name) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const char c : name) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

// SDFormat's <pose> x y z roll pitch yaw (URDF's rpy convention, urdfdom's).
Eigen::Isometry3d poseOf(const std::array<double, 6>& pose) {
  urdf::Rotation rotation;
  rotation.setFromRPY(pose[3], pose[4], pose[5]);
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  out.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  return out;
}

// A sensor's handle is named after the topic its gazebo_ros plugin
// publishes on, so ros_controllers' sensor controllers (which publish on the
// handle's name) publish where Gazebo would; without a plugin, the sensor's name.
std::string handleName(const SensorDescription& sensor) {
  std::string topic = sensor.topic;
  while (!topic.empty() && topic.front() == '/') topic.erase(topic.begin());
  return topic.empty() ? sensor.name : topic;
}

std::array<double, 9> diagonal(double a, double b, double c) { return {a, 0, 0, 0, b, 0, 0, 0, c}; }

// mean + stddev · N(0, 1); `unit` keeps the second value of each pair it draws.
double sample(std::mt19937_64& generator, std::normal_distribution<double>& unit, double mean, double stddev) noexcept {
  if (stddev <= 0.0) return mean;
  return mean + stddev * unit(generator);
}

}  // namespace

bool SimulatedSensors::Sampling::due(double time_s) noexcept {
  if (period_s <= 0.0) return true;
  // A small tolerance, so a rate that divides the step rate samples on its steps.
  if (time_s + 1e-9 < next_s) return false;
  next_s += period_s;
  if (next_s <= time_s) next_s = time_s + period_s;  // fell behind (e.g. after a reset)
  return true;
}

void SimulatedSensors::init(const std::vector<SensorDescription>& sensors, const urdf::ModelInterface& model,
                            PhysicsEngine& engine, const Eigen::Vector3d& gravity, const std::string& source_name) {
  engine_ = &engine;
  gravity_ = gravity;
  imus_.clear();
  force_torques_.clear();
  contacts_.clear();
  std::size_t imu_count = 0;
  std::size_t force_torque_count = 0;
  std::size_t contact_count = 0;
  for (const SensorDescription& sensor : sensors) {
    imu_count += sensor.type == SensorType::imu;
    force_torque_count += sensor.type == SensorType::force_torque;
    contact_count += sensor.type == SensorType::contact;
  }
  // Sized once: the handles point into these elements.
  imus_.reserve(imu_count);
  force_torques_.reserve(force_torque_count);
  contacts_.reserve(contact_count);
  for (const SensorDescription& sensor : sensors) {
    const auto fail = [&](const ConfigError& error) {
      return ConfigError(sensor.element + ": " + error.what());
    };
    const double period = sensor.update_rate_hz > 0.0 ? 1.0 / sensor.update_rate_hz : 0.0;
    if (sensor.type == SensorType::imu) {
      Imu imu;
      imu.name = handleName(sensor);
      imu.frame_id = sensor.frame_id.empty() ? sensor.reference : sensor.frame_id;
      try {
        imu.link = engine.trackLink(sensor.reference);
      } catch (const ConfigError& error) {
        throw fail(error);
      }
      imu.sensor_in_link = poseOf(sensor.pose);
      imu.sampling.period_s = period;
      imu.seed = seedOf(sensor.name);
      for (std::size_t axis = 0; axis < 3; ++axis) {
        imu.angular_velocity_noise[axis].model = sensor.angular_velocity_noise[axis];
        imu.linear_acceleration_noise[axis].model = sensor.linear_acceleration_noise[axis];
        imu.orientation_noise[axis].model = sensor.orientation_noise;
      }
      const auto covariance = [](const std::array<Noise, 3>& noise) {
        const auto variance = [](const Noise& n) { return n.model.stddev * n.model.stddev; };
        return diagonal(variance(noise[0]), variance(noise[1]), variance(noise[2]));
      };
      imu.orientation_covariance = covariance(imu.orientation_noise);
      imu.angular_velocity_covariance = covariance(imu.angular_velocity_noise);
      imu.linear_acceleration_covariance = covariance(imu.linear_acceleration_noise);
      imus_.push_back(std::move(imu));
    } else if (sensor.type == SensorType::force_torque) {
      ForceTorque ft;
      ft.name = handleName(sensor);
      const urdf::JointConstSharedPtr joint = model.getJoint(sensor.reference);
      if (!joint) throw ConfigError(sensor.element + ": no joint '" + sensor.reference + "' in " + source_name);
      ft.frame_id = sensor.frame_id.empty() ? joint->child_link_name : sensor.frame_id;
      try {
        ft.joint = engine.trackJointWrench(sensor.reference);
        if (sensor.frame == ForceTorqueFrame::parent) {
          ft.child_link = engine.trackLink(joint->child_link_name);
          ft.parent_link = engine.trackLink(joint->parent_link_name);
        }
      } catch (const ConfigError& error) {
        throw fail(error);
      }
      ft.frame = sensor.frame;
      ft.sign = sensor.measure_direction == ForceTorqueDirection::child_to_parent ? -1.0 : 1.0;
      ft.sensor_from_child = poseOf(sensor.pose).linear().transpose();
      ft.sampling.period_s = period;
      ft.seed = seedOf(sensor.name);
      ft.noise.model = sensor.wrench_noise;
      force_torques_.push_back(std::move(ft));
    } else if (sensor.type == SensorType::contact) {
      Contact contact;
      contact.name = sensor.name;
      contact.frame_id = sensor.frame_id.empty() ? "world" : sensor.frame_id;
      contact.collision = model.getName() + "::" + sensor.reference + "::" + sensor.reference + "_collision";
      contact.topic = sensor.topic.empty() ? sensor.name : sensor.topic;
      contact.update_rate_hz = sensor.update_rate_hz;
      try {
        contact.tracked = engine.trackContacts(sensor.reference);
        contact.link = engine.trackLink(sensor.reference);
      } catch (const ConfigError& error) {
        throw fail(error);
      }
      contact.sampling.period_s = period;
      contact.scratch.resize(hi::ContactSensorReading::kCapacity);
      contacts_.push_back(std::move(contact));
    }
  }
  reset(0.0);
}

void SimulatedSensors::registerInterfaces(hi::InterfaceManager& hardware) {
  for (Imu& imu : imus_) {
    hi::ImuSensorHandle::Data data;
    data.name = imu.name;
    data.frame_id = imu.frame_id;
    data.orientation = imu.orientation.data();
    data.orientation_covariance = imu.orientation_covariance.data();
    data.angular_velocity = imu.angular_velocity.data();
    data.angular_velocity_covariance = imu.angular_velocity_covariance.data();
    data.linear_acceleration = imu.linear_acceleration.data();
    data.linear_acceleration_covariance = imu.linear_acceleration_covariance.data();
    imu_interface_.registerHandle(hi::ImuSensorHandle(data));
  }
  for (ForceTorque& ft : force_torques_) {
    force_torque_interface_.registerHandle(
        hi::ForceTorqueSensorHandle(ft.name, ft.frame_id, ft.force.data(), ft.torque.data()));
  }
  for (Contact& contact : contacts_) {
    hi::ContactSensorHandle::Data data;
    data.name = contact.name;
    data.frame_id = contact.frame_id;
    data.collision = contact.collision;
    data.topic = contact.topic;
    data.update_rate_hz = contact.update_rate_hz;
    data.reading = &contact.reading;
    contact_interface_.registerHandle(hi::ContactSensorHandle(data));
  }
  if (!contacts_.empty()) hardware.registerInterface(&contact_interface_);
  if (!imus_.empty()) hardware.registerInterface(&imu_interface_);
  if (!force_torques_.empty()) hardware.registerInterface(&force_torque_interface_);
}

void SimulatedSensors::reset(double time_s) noexcept {
  const auto draw_biases = [](std::mt19937_64& generator, std::normal_distribution<double>& unit, auto& noises) {
    for (Noise& noise : noises) {
      noise.bias = sample(generator, unit, noise.model.bias_mean, noise.model.bias_stddev);
      // SDFormat's bias: its sign is random.
      if (noise.bias != 0.0 && std::uniform_int_distribution<int>(0, 1)(generator) == 1) noise.bias = -noise.bias;
    }
  };
  for (Imu& imu : imus_) {
    imu.generator.seed(imu.seed);
    imu.unit.reset();
    draw_biases(imu.generator, imu.unit, imu.angular_velocity_noise);
    draw_biases(imu.generator, imu.unit, imu.linear_acceleration_noise);
    draw_biases(imu.generator, imu.unit, imu.orientation_noise);
    imu.has_last = false;
    imu.sampling.next_s = time_s;
  }
  for (ForceTorque& ft : force_torques_) {
    ft.generator.seed(ft.seed);
    ft.unit.reset();
    std::array<Noise, 1> noise{ft.noise};
    draw_biases(ft.generator, ft.unit, noise);
    ft.noise = noise[0];
    ft.sampling.next_s = time_s;
  }
  for (Contact& contact : contacts_) {
    contact.sampling.next_s = time_s;
    contact.reading.count = 0;
    contact.reading.dropped = 0;
  }
  update(time_s);
}

void SimulatedSensors::update(double time_s) noexcept {
  for (Imu& imu : imus_) sampleImu(imu, time_s);
  for (ForceTorque& ft : force_torques_) {
    if (ft.sampling.due(time_s)) sampleForceTorque(ft);
  }
  for (Contact& contact : contacts_) {
    if (contact.sampling.due(time_s)) sampleContacts(contact);
  }
}

void SimulatedSensors::sampleContacts(Contact& sensor) noexcept {
  const std::size_t count = engine_->readContacts(sensor.tracked, sensor.scratch);
  const std::size_t kept = std::min(count, sensor.scratch.size());
  hi::ContactSensorReading& reading = sensor.reading;
  EngineLinkState link;
  engine_->readLinkState(sensor.link, link);
  for (int axis = 0; axis < 3; ++axis) reading.link_position[axis] = link.position[axis];
  for (std::size_t k = 0; k < kept; ++k) {
    const EngineContact& contact = sensor.scratch[k];
    hi::ContactPoint& point = reading.points[k];
    static const std::string kNone;
    const std::string& other = contact.other != nullptr ? *contact.other : kNone;
    const std::size_t length = std::min(other.size(), point.other_collision.size() - 1);
    std::copy_n(other.data(), length, point.other_collision.data());
    point.other_collision[length] = '\0';
    for (int axis = 0; axis < 3; ++axis) {
      point.position[axis] = contact.position[axis];
      point.normal[axis] = contact.normal[axis];
      point.force[axis] = contact.force[axis];
    }
    point.depth = contact.depth;
  }
  reading.count = kept;
  reading.dropped = count - kept;
}

void SimulatedSensors::sampleImu(Imu& imu, double time_s) noexcept {
  EngineLinkState link;
  engine_->readLinkState(imu.link, link);
  const Eigen::Matrix3d world_from_link = link.orientation.toRotationMatrix();
  const Eigen::Matrix3d world_from_sensor = world_from_link * imu.sensor_in_link.linear();
  const Eigen::Vector3d offset = world_from_link * imu.sensor_in_link.translation();
  const Eigen::Vector3d velocity = link.linear_velocity + link.angular_velocity.cross(offset);

  // The acceleration since the last read; none known yet: at rest.
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  if (imu.has_last && time_s > imu.last_time_s) {
    acceleration = (velocity - imu.last_velocity) / (time_s - imu.last_time_s);
  }
  if (!imu.has_last || time_s > imu.last_time_s) {
    imu.last_velocity = velocity;
    imu.last_time_s = time_s;
    imu.has_last = true;
  }
  if (!imu.sampling.due(time_s)) return;

  const Eigen::Vector3d angular = world_from_sensor.transpose() * link.angular_velocity;
  const Eigen::Vector3d specific_force = world_from_sensor.transpose() * (acceleration - gravity_);
  Eigen::Vector3d turn;
  for (int axis = 0; axis < 3; ++axis) {
    const auto a = static_cast<std::size_t>(axis);
    const auto noisy = [&](Noise& noise, double value) {
      if (noise.model.none()) return value;
      return value + noise.bias + sample(imu.generator, imu.unit, noise.model.mean, noise.model.stddev);
    };
    imu.angular_velocity[a] = noisy(imu.angular_velocity_noise[a], angular[axis]);
    imu.linear_acceleration[a] = noisy(imu.linear_acceleration_noise[a], specific_force[axis]);
    turn[axis] = noisy(imu.orientation_noise[a], 0.0);
  }
  Eigen::Quaterniond orientation(world_from_sensor);
  const double angle = turn.norm();
  if (angle > 0.0) orientation = orientation * Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle));
  orientation.normalize();
  imu.orientation = {orientation.x(), orientation.y(), orientation.z(), orientation.w()};
}

void SimulatedSensors::sampleForceTorque(ForceTorque& ft) noexcept {
  EngineJointWrench wrench;
  engine_->readJointWrench(ft.joint, wrench);
  Eigen::Vector3d force = ft.sign * wrench.force;
  Eigen::Vector3d torque = ft.sign * wrench.torque;
  switch (ft.frame) {
    case ForceTorqueFrame::child:
      break;
    case ForceTorqueFrame::parent: {
      EngineLinkState child;
      EngineLinkState parent;
      engine_->readLinkState(ft.child_link, child);
      engine_->readLinkState(ft.parent_link, parent);
      const Eigen::Matrix3d parent_from_child = (parent.orientation.conjugate() * child.orientation).toRotationMatrix();
      force = parent_from_child * force;
      torque = parent_from_child * torque;
      break;
    }
    case ForceTorqueFrame::sensor:
      force = ft.sensor_from_child * force;
      torque = ft.sensor_from_child * torque;
      break;
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    double f = force[static_cast<int>(axis)];
    double t = torque[static_cast<int>(axis)];
    if (!ft.noise.model.none()) {
      f += ft.noise.bias + sample(ft.generator, ft.unit, ft.noise.model.mean, ft.noise.model.stddev);
      t += ft.noise.bias + sample(ft.generator, ft.unit, ft.noise.model.mean, ft.noise.model.stddev);
    }
    ft.force[axis] = f;
    ft.torque[axis] = t;
  }
}

}  // namespace servoloop::sim_common
