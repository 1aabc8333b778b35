// One robot of a node: its hardware, bus, manager and loop, and its
// controllers. How its loop is driven: robot_loop_driver.cpp; its safety
// states: robot_safety.cpp.
#include "servoloop/node/robot_instance.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "servoloop/hardware_interface/hardware_info.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/hardware_interface/joint_interfaces.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/simulatable_urdf.hpp"
#include "servoloop/description/xacro.hpp"
#include "servoloop/node/ground_truth_publisher.hpp"
#include "servoloop/controller_manager/wall_clock_loop.hpp"
#include "servoloop/realtime/messages.hpp"

namespace servoloop::node {
namespace {

// Writes one world setting to the robot's sim/ parameters, where the backend
// reads it, warning when a parameter file said otherwise.
template <class T>
void setWorldParameter(params::ParameterStore& store, const std::string& name, const T& value, bool differs_from_file) {
  if (store.has(name) && differs_from_file) {
    logger().warn("parameter '{}' ({}) is replaced by the launch file's world setting", name, store.sourceOf(name));
  }
  store.set(name, value);
}

void writeWorldSettings(params::ParameterStore& store, const std::string& ns, const WorldSettings& world) {
  const std::string sim = params::resolveName(ns, "sim");
  const std::string time_step = sim + "/time_step";
  const std::string gravity = sim + "/gravity";
  const std::string ground_plane = sim + "/ground_plane";
  setWorldParameter(store, time_step, world.time_step_s,
                    store.get<double>(time_step, world.time_step_s) != world.time_step_s);
  const std::vector<double> gravity_value(world.gravity.begin(), world.gravity.end());
  setWorldParameter(store, gravity, gravity_value, store.get<std::vector<double>>(gravity, gravity_value) != gravity_value);
  setWorldParameter(store, ground_plane, world.ground_plane,
                    store.get<bool>(ground_plane, world.ground_plane) != world.ground_plane);
}

// The launch file's (or spawn request's) base, pose and self-collision
// settings, written where the backend reads them; they win over a parameter file.
void writeSpawnSettings(params::ParameterStore& store, const std::string& ns, const RobotSpec& spec) {
  const std::string sim = params::resolveName(ns, "sim");
  if (spec.fixed_base) store.set(sim + "/fixed_base", *spec.fixed_base);
  if (spec.self_collide) store.set(sim + "/self_collide", *spec.self_collide);
  if (spec.pose) store.set(sim + "/pose", std::vector<double>(spec.pose->begin(), spec.pose->end()));
}

}  // namespace

RobotInstance::RobotInstance(const RobotSpec& spec, const RobotWorld& world)
    : urdf_path_(spec.urdf),
      backend_name_(spec.hardware_type.empty() ? world.world.backend : spec.hardware_type),
      real_time_factor_(world.real_time_factor),
      realtime_(spec.realtime ? *spec.realtime : world.realtime) {
  if (!world.plugins || world.parameters == nullptr) {
    throw Error("RobotInstance: the world's plugin loader and parameter store must be set");
  }
  params::ParameterStore& store = *world.parameters;

  const bool hardware_robot = !spec.hardware_type.empty();
  // The hardware first (whether it simulates decides what it is given): a
  // simulation backend, or the launch file's hardware plugin.
  try {
    backend_ = world.plugins->create<hardware_interface::RobotHW>(backend_name_);
  } catch (const Error& e) {
    throw ConfigError(hardware_robot
                          ? fmt::format("hardware '{}' ({}): {}; name a robot_hw plugin (`servoloop control "
                                        "list-types --kind robot_hw` lists them; --plugin-dir or "
                                        "SERVOLOOP_PLUGIN_PATH add folders)",
                                        backend_name_, spec.hardware_source, e.what())
                          : fmt::format("backend '{}': {}; choose another with --backend or world.backend",
                                        backend_name_, e.what()));
  }
  hw_ = backend_.get();
  sim_hw_ = dynamic_cast<hardware_interface::SimulatedRobotHW*>(hw_);
  if (sim_hw_ == nullptr && !hardware_robot) {
    throw ConfigError(fmt::format(
        "backend '{}' is a robot_hw plugin but not a simulator (it does not implement SimulatedRobotHW); "
        "a world's backend must simulate (bullet, mujoco, mock); to drive hardware, name the plugin in the "
        "robot's `hardware: {{type: {}}}`",
        backend_name_, backend_name_));
  }

  // Robot description and namespace.
  robot_description_ = spec.description.empty() ? readRobotDescription(spec.urdf, spec.xacro_args) : spec.description;
  // A simulator (also one standing in for hardware, `hardware: {type: mock}`)
  // gets the description without what it cannot simulate, as in Gazebo;
  // hardware moves every joint, massless links or not, and gets it whole.
  std::string xml = robot_description_;
  if (sim_hw_ != nullptr) {
    SimulatableUrdf simulatable = simulatableUrdf(robot_description_, spec.urdf.string());
    xml = std::move(simulatable.xml);
    left_out_joints_ = std::move(simulatable.skipped_joints);
  }
  parameters_ = &store;
  // Hardware: urdfdom's parse without the checks of what a simulator needs
  // (every moving link's mass and inertia, collision meshes).
  model_ = sim_hw_ != nullptr ? parseRobotModel(xml, spec.urdf.string())
                              : parseUrdfWithUrdfdom(xml, spec.urdf.string(), /*report_warnings=*/true);
  robot_name_ = spec.model.empty() ? model_->getName() : spec.model;
  namespace_ = resolveRobotNamespace(xml, spec.urdf.string(), spec.robot_namespace, robot_name_);
  if (const std::string ignored = ignoredLaunchNamespace(xml, spec.urdf.string(), spec.robot_namespace);
      !ignored.empty()) {
    logger().warn("{}", ignored);
  }
  if (hardware_robot) {
    // The plugin's parameters, where it reads them: <ns>/hardware.
    store.loadString(spec.hardware_params_yaml, spec.hardware_source, params::resolveName(namespace_, "hardware"));
  } else {
    writeWorldSettings(store, namespace_, world.world);
  }
  writeSpawnSettings(store, namespace_, spec);

  // A simulated robot in lockstep lives in the node's world: built into its
  // physics, its cycles run by the world's loop.
  const bool joins_world = sim_hw_ != nullptr && !hardware_robot && !world.world.wall_clock;
  if (joins_world && (world.world_loop == nullptr || world.simulated_world == nullptr)) {
    throw Error("RobotInstance: a simulated robot in lockstep runs in its world; set RobotWorld::simulated_world "
                "and RobotWorld::world_loop");
  }
  if (joins_world) {
    try {
      sim_hw_->joinWorld(*world.simulated_world);
    } catch (const std::exception& e) {
      throw ConfigError(fmt::format("backend '{}': robot '{}': {}", backend_name_, namespace_, e.what()));
    }
    world_loop_ = world.world_loop;
    if (spec.realtime) {
      logger().warn("robot '{}': its own realtime: settings do not apply; its cycles run on the world's loop "
                    "thread, which takes the launch file's realtime: settings",
                    namespace_);
    }
  }

  hardware_interface::HardwareInfo info;
  info.urdf_xml = xml;
  info.urdf_path = spec.urdf.string();
  info.robot_namespace = namespace_;
  if (store.has(namespace_)) info.parameters = store.node(namespace_);
  // The exception comes from the backend's library, which may be unloaded
  // with backend_ when this constructor unwinds; its message is copied into
  // an exception of the node's own while the library is still loaded.
  try {
    hw_->init(info);
  } catch (const ConfigError& e) {
    throw ConfigError(fmt::format("backend '{}': {}", backend_name_, e.what()));
  } catch (const std::exception& e) {
    throw Error(fmt::format("backend '{}' failed to initialise the robot: {}", backend_name_, e.what()));
  } catch (...) {
    throw Error(fmt::format("backend '{}' failed to initialise the robot with an exception that is not a "
                            "std::exception",
                            backend_name_));
  }

  // Topics, controllers and the loop.
  bus_ = std::make_unique<realtime::TopicBus>();
  bus_->start();
  controller_manager::ControllerContext context;
  context.robot_namespace = namespace_;
  context.topics = bus_.get();
  actions_ = std::make_unique<realtime::ActionRegistry>();
  context.actions = actions_.get();
  context.parameters = &store;
  context.robot_model = model_;
  if (!(world.update_rate_hz > 0.0) && sim_hw_ == nullptr) {
    throw ConfigError(fmt::format("robot '{}': hardware '{}' runs at the controller manager's rate, and none is "
                                  "given; set controller_manager: {{update_rate: 1000}} (Hz)",
                                  namespace_, backend_name_));
  }
  const double update_rate_hz =
      world.update_rate_hz > 0.0 ? world.update_rate_hz : 1.0 / sim_hw_->timeStep().seconds;
  params::ParameterStore* store_ptr = &store;
  const std::string ns = namespace_;
  auto lookup = [store_ptr, ns](const std::string& controller) {
    const std::string name = params::resolveName(ns, controller);
    return store_ptr->has(name) ? store_ptr->node(name) : YAML::Node();
  };
  manager_ = std::make_unique<controller_manager::ControllerManager>(
      hw_, std::make_shared<node::PluginControllerFactory>(world.plugins), lookup, context, update_rate_hz);
  safety_ = std::make_unique<controller_manager::SafetySupervisor>(*hw_);
  manager_->setSwitchGuard([this](const controller_manager::SwitchRequest& request) { return switchRefusal(request); });
  estop_subscription_ = bus_->subscribe<std_msgs::Bool>(
      params::resolveName(namespace_, "estop"), [this](const std_msgs::Bool& msg) {
        const controller_manager::ServiceResult done =
            setEmergencyStop(msg.data, controller_manager::EmergencyStopSource::topic);
        if (!done) logger().error("robot '{}': estop topic: {}", namespace_, done.message);
      });
  createLoop(hardware_robot, hardware_robot || world.world.wall_clock, update_rate_hz);
  loadControllers(spec, store);
}

void RobotInstance::createLoop(bool hardware_robot, bool wall_clock, double update_rate_hz) {
  controller_manager::LoopCommonOptions common;
  common.topic_bus = bus_.get();
  common.safety = safety_.get();
  if (sim_hw_ != nullptr && GroundTruthPublisher::applies(*sim_hw_)) {
    const std::string topic = params::resolveName(namespace_, "ground_truth/odom");
    ground_truth_ = std::make_unique<GroundTruthPublisher>(*sim_hw_, *bus_, topic, model_->getRoot()->name);
    common.cycle_hook = ground_truth_.get();
    logger().info("robot '{}': floating base; its ground truth is published on {} (nav_msgs/Odometry, {} Hz)",
                  namespace_, topic, GroundTruthPublisher::kDefaultRateHz);
  }
  auto* contacts = sim_hw_ != nullptr ? sim_hw_->get<hardware_interface::ContactSensorInterface>() : nullptr;
  if (contacts != nullptr && wall_clock) {
    logger().warn("robot '{}': its contact sensors publish only in a simulated world's loop, not on the wall clock",
                  namespace_);
  } else if (contacts != nullptr) {
    const double dt = sim_hw_->timeStep().seconds;
    const auto steps_per_cycle = static_cast<std::uint64_t>(std::max(1.0, std::round(1.0 / (update_rate_hz * dt))));
    contact_states_ = std::make_unique<ContactStatesPublisher>(*contacts, *bus_, namespace_, dt, steps_per_cycle);
    for (const std::string& topic : contact_states_->topics()) {
      logger().info("robot '{}': contact sensor on {} (gazebo_msgs/ContactsState)", namespace_, topic);
    }
  }
  try {
    if (wall_clock) {
      controller_manager::WallClockLoop::Options options;
      static_cast<controller_manager::LoopCommonOptions&>(options) = common;
      options.step_simulation = true;  // a simulated robot standing in for hardware
      loop_ = std::make_unique<controller_manager::WallClockLoop>(*hw_, *manager_, options);
      logger().info("robot '{}': '{}' runs on the wall clock at {} Hz", namespace_, backend_name_, update_rate_hz);
    } else {
      controller_manager::SimulationLoop::Options options;
      static_cast<controller_manager::LoopCommonOptions&>(options) = common;
      options.real_time_factor = real_time_factor_;
      auto loop = std::make_unique<controller_manager::SimulationLoop>(*sim_hw_, *manager_, options);
      sim_loop_ = loop.get();
      loop_ = std::move(loop);
    }
  } catch (const ConfigError& e) {
    throw ConfigError(hardware_robot
                          ? fmt::format("robot '{}': controller_manager.update_rate {} Hz: {}", namespace_,
                                        update_rate_hz, e.what())
                          : fmt::format("robot '{}': controller_manager.update_rate {} Hz with world.time_step {} s: {}",
                                        namespace_, update_rate_hz, sim_hw_->timeStep().seconds, e.what()));
  }
}

RobotInstance::~RobotInstance() {
  stop();
  try {
    shutdownControllers();
  } catch (const std::exception& e) {
    logger().error("robot '{}': shutting down its controllers failed: {}", namespace_, e.what());
  }
  loop_.reset();
  manager_.reset();
  if (bus_) bus_->stop();
}

void RobotInstance::loadControllers(const RobotSpec& spec, const params::ParameterStore& store) {
  (void)store;
  const auto load = [&](const std::string& name) {
    if (loadController(name)) return true;
    launch_failures_.push_back("controller '" + name + "' did not load");
    return false;
  };
  // Stopped ones first: they include the fallbacks a started one may name
  // (a fallback must be loaded before its controller).
  for (const std::string& name : spec.stopped_controllers) load(name);
  for (const std::string& name : spec.controllers) {
    if (load(name)) launch_controllers_.push_back(name);
  }
}

namespace {

// Every scalar value in a controller's parameters (maps and sequences walked;
// `type` left out): wherever a controller names its joints — `joint`,
// `joints`, `left_wheel`, a plugin's own key — the names are among them.
void collectScalars(const YAML::Node& node, std::vector<std::string>& out) {
  if (node.IsScalar()) {
    out.push_back(node.Scalar());
  } else if (node.IsSequence()) {
    for (const YAML::Node& item : node) collectScalars(item, out);
  } else if (node.IsMap()) {
    for (const auto& entry : node) {
      if (entry.first.IsScalar() && entry.first.Scalar() == "type") continue;
      collectScalars(entry.second, out);
    }
  }
}

}  // namespace

controller_manager::ServiceResult RobotInstance::loadController(const std::string& name) {
  std::string left_out;
  if (!left_out_joints_.empty() && parameters_ != nullptr) {
    try {
      const std::string params_name = params::resolveName(namespace_, name);
      std::vector<std::string> values;
      if (parameters_->has(params_name)) collectScalars(parameters_->node(params_name), values);
      for (const std::string& value : values) {
        if (std::find(left_out_joints_.begin(), left_out_joints_.end(), value) != left_out_joints_.end()) {
          left_out = value;
          break;
        }
      }
    } catch (const std::exception&) {
      // A name or parameters the manager refuses: its load says why.
    }
  }
  if (parameters_ != nullptr) {
    // A type the manager would miss under the namespace but the parameters
    // hold elsewhere: one error that says where it is and how to load it.
    std::string elsewhere;
    try {
      elsewhere = whereParametersAre(name, *parameters_);
    } catch (const std::exception&) {
      // A name the manager refuses: its load says why.
    }
    if (!elsewhere.empty()) {
      const std::string why = fmt::format("load controller '{}': {}", name, elsewhere);
      logger().error("{}", why);
      return controller_manager::ServiceResult::failure(why);
    }
  }
  if (!left_out.empty()) {
    const std::string why = fmt::format(
        "robot '{}': controller '{}' names joint '{}', which the simulation left out because the link it moves, or "
        "a link above it, has no mass (the node's warning at start names that link); give the link an <inertial> "
        "with <mass value> > 0 and an <inertia>",
        namespace_, name, left_out);
    logger().error("{}", why);
    return controller_manager::ServiceResult::failure(why);
  }
  return manager_->loadController(name);
}

// A controller whose type is not under the robot's namespace often sits
// elsewhere: a file of top-level controllers loaded at "/" (ROS loads it into
// the namespace with <rosparam ns=...>), or a file that nests its controllers
// under the namespace and was loaded into it as well. Says where its type was
// found and the fix; empty when the type is where the manager looks, or
// nowhere (the manager's own error says to add it).
std::string RobotInstance::whereParametersAre(const std::string& name, const params::ParameterStore& store) const {
  const std::string expected = params::resolveName(namespace_, name) + "/type";
  if (store.has(expected)) return "";
  const std::string suffix = "/" + name + "/type";
  std::string found;
  std::string deeper;  // the extra level of a file that already nests its controllers under the namespace
  const std::string ns_prefix = namespace_ == "/" ? "/" : namespace_ + "/";
  for (const std::string& key : store.list("/")) {
    if (key.size() >= suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) {
      found += (found.empty() ? "'" : ", '") + key + "'";
      const std::string holder = key.substr(0, key.size() - suffix.size());
      if (holder.size() > ns_prefix.size() && holder.compare(0, ns_prefix.size(), ns_prefix) == 0) {
        deeper = holder.substr(ns_prefix.size());
      }
    }
  }
  if (found.empty()) return "";
  if (!deeper.empty()) {
    // Loaded with ns: into the robot's namespace although the file nests its
    // controllers under it already: the usual fix (add ns:) is what was done.
    return fmt::format("parameter '{}' is missing, but the parameters have {}: the file nests its controllers under "
                       "'{}:' and was loaded into '{}' too; load it without `ns:` (or remove that level from the file)",
                       expected, found, deeper, namespace_);
  }
  return fmt::format(
      "parameter '{}' is missing, but the parameters have {}: the controller YAML was loaded outside the robot's "
      "namespace; load it into it with `ns:` (params: [{{file: FILE.yaml, ns: {}}}], as <rosparam ns=...> does) or "
      "move the controller under '{}'",
      expected, found, namespace_, namespace_);
}

// Loop thread, before the first physics step. In the manager, a controller
// started in cycle c first updates in cycle c + d (d: its rate divisor) with
// the period since its start. So each controller is started d control
// periods before t = 0, in manager updates that step no physics and update
// no running controller (every one started is still short of its first d
// cycles): all of them first update at t = 0 with their nominal period, then
// every d cycles (a 100 Hz controller at 0, 10 ms, 20 ms, ...). The hardware
// is read first, so starting() sees the measured state. Controllers with
// different divisors start in separate STRICT switches, largest divisor
// first; one that cannot start is reported and the others run.
void RobotInstance::startLaunchControllers() {
  startControllersAtStart(launch_controllers_, [this](const std::vector<std::string>& controllers, const std::string& why) {
    reportLaunchStartFailure(controllers, why);
  });
}

// Controllers with a slower rate start first, so that each one's first
// update comes at t = 0: at -k control periods for a divisor of k.
void RobotInstance::startControllersAtStart(const std::vector<std::string>& names, const StartFailure& failed) {
  if (names.empty()) return;
  std::map<std::uint32_t, std::vector<std::string>, std::greater<>> by_divisor;
  for (const controller_manager::ControllerSpec& controller : manager_->listControllers()) {
    if (std::find(names.begin(), names.end(), controller.name) != names.end()) {
      by_divisor[std::max<std::uint32_t>(controller.update_divisor, 1)].push_back(controller.name);
    }
  }
  if (by_divisor.empty()) return;

  const Duration period = loop_->controlPeriod();
  if (hw_->read(Time(0.0), sim_loop_ != nullptr ? sim_loop_->physicsStep() : period) != ReturnType::ok) {
    logger().warn("robot '{}': reading the hardware before starting the controllers failed", namespace_);
  }
  for (std::uint32_t cycles_before = by_divisor.begin()->first; cycles_before >= 1; --cycles_before) {
    const Time time(-static_cast<double>(cycles_before) * period.seconds);
    if (const auto group = by_divisor.find(cycles_before); group != by_divisor.end()) {
      controller_manager::SwitchRequest request;
      request.start_controllers = group->second;
      request.strictness = controller_manager::SwitchStrictness::STRICT;
      // A client's switch that got in first is carried out by this cycle's
      // update; ours follows in the next one.
      if (manager_->switchPending()) manager_->update(time, period);
      if (const controller_manager::ServiceResult result = manager_->requestSwitch(request); !result) {
        failed(group->second, result.message);
      } else {
        manager_->update(time, period);
        if (const controller_manager::ServiceResult done = manager_->finishSwitch(); !done) {
          failed(group->second, done.message);
        }
        continue;
      }
    }
    manager_->update(time, period);
  }
}

void RobotInstance::reportLaunchStartFailure(const std::vector<std::string>& controllers, const std::string& why) {
  logger().error("robot '{}': starting controllers failed: {}", namespace_, why);
  std::string names;
  for (const std::string& name : controllers) names += (names.empty() ? "'" : ", '") + name + "'";
  launch_failures_.push_back("controller(s) " + names + " did not start: " + why);
}

void RobotInstance::shutdownControllers() {
  if (controllers_shut_down_ || !manager_) return;
  controllers_shut_down_ = true;
  controller_manager::SwitchRequest request;
  request.strictness = controller_manager::SwitchStrictness::BEST_EFFORT;
  for (const controller_manager::ControllerSpec& controller : manager_->listControllers()) {
    if (controller.state == controller_manager::ControllerState::running) request.stop_controllers.push_back(controller.name);
  }
  const Time now(simTime());
  if (!request.stop_controllers.empty() && manager_->requestSwitch(request)) {
    // The loop has ended: this thread is the real-time side now, and one
    // update carries the switch out (stopping() runs) without stepping physics.
    manager_->update(now, loop_->controlPeriod());
  }
  // Newest first: a fallback is loaded before the controller naming it, and
  // must be unloaded after it.
  const std::vector<controller_manager::ControllerSpec> loaded = manager_->listControllers();
  for (auto it = loaded.rbegin(); it != loaded.rend(); ++it) manager_->unloadController(it->name);
}

double RobotInstance::simTime() const {
  if (sim_loop_ == nullptr) return loop_->statistics().simTime();
  return stepsToSeconds(sim_loop_->stepsTaken(), sim_loop_->physicsStep().seconds);
}

std::vector<JointReading> RobotInstance::joints() const {
  std::vector<JointReading> readings;
  auto* state = hw_->get<hardware_interface::JointStateInterface>();
  if (state == nullptr) return readings;
  for (const std::string& name : state->getNames()) {
    const auto handle = state->getHandle(name);
    readings.push_back({name, handle.getPosition(), handle.getVelocity(), handle.getEffort()});
  }
  return readings;
}

std::vector<std::pair<std::string, std::vector<std::string>>> RobotInstance::jointInterfaces() const {
  std::map<std::string, std::vector<std::string>> by_joint;
  for (const std::string& iface_name : hw_->getNames()) {
    const bool joint_interface = iface_name == "JointStateInterface" ||
                                 (iface_name.size() > 14 && iface_name.ends_with("JointInterface"));
    if (!joint_interface) continue;
    for (const std::string& joint : hw_->getByName(iface_name)->getNames()) by_joint[joint].push_back(iface_name);
  }
  // JointStateInterface first, the command interfaces after it.
  std::vector<std::pair<std::string, std::vector<std::string>>> joints;
  for (auto& [joint, interfaces] : by_joint) {
    std::stable_partition(interfaces.begin(), interfaces.end(),
                          [](const std::string& name) { return name == "JointStateInterface"; });
    joints.emplace_back(joint, std::move(interfaces));
  }
  return joints;
}

}  // namespace servoloop::node
