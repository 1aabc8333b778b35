// ControllerManager: construction, load/unload, listing, library reload and
// fault reporting. Switching is in controller_switching.cpp, the real-time
// cycle in controller_scheduling.cpp.
#include "servoloop/controller_manager/controller_manager.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>
#include <utility>

#include "asymmetric_fence.hpp"
#include "controller_entry.hpp"
#include "servoloop/controller_manager/loop_clock.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/params/parameters_yaml.hpp"
#include "servoloop/params/schema.hpp"

namespace servoloop::controller_manager {

namespace {
// "<ns>/<name>/<key>", the ros_control parameter path users know.
std::string parameterPath(const std::string& robot_namespace, const std::string& name,
                          const std::string& key) {
  std::string path = robot_namespace;
  if (!path.empty() && path.back() != '/') path += '/';
  return path + name + "/" + key;
}

// The keys of a controller's YAML map that the manager reads; the rest are the
// controller's own.
const params::Schema& managerKeysSchema() {
  using params::ValueType;
  static const params::Schema schema(
      "controller manager's keys",
      {
          {"type", ValueType::text, "the controller type, e.g. effort_controllers/JointPositionController"},
          {"update_rate", ValueType::number,
           "how often the controller updates (Hz); 0 or absent: every cycle of the manager", {.min = 0.0}},
          {"fallback_controllers", ValueType::text_list,
           "loaded controllers started when this one faults, e.g. [arm_hold_controller]"},
      },
      params::UnknownKeys::allow);
  return schema;
}

std::string formatRate(double hz) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g Hz", hz);
  return text;
}
// The update rate a controller runs at: the requested one when it divides
// the manager's, otherwise the nearest that does, with a warning saying so.
UpdateRateChoice chooseRateOrWarn(const std::string& name, double manager_rate_hz, double requested_rate_hz) {
  const UpdateRateChoice rate = chooseUpdateRate(manager_rate_hz, requested_rate_hz);
  if (rate.exact) return rate;
  if (manager_rate_hz <= 0.0) {
    logger().warn(
        "controller '{}': update_rate {} ignored: the controller manager runs at no fixed "
        "rate, so the controller updates every cycle",
        name, formatRate(requested_rate_hz));
  } else {
    logger().warn(
        "controller '{}': update_rate {} is not a divisor of the controller manager's "
        "update_rate {}; running it at {} (every {} cycles) instead",
        name, formatRate(requested_rate_hz), formatRate(manager_rate_hz), formatRate(rate.rate_hz), rate.divisor);
  }
  return rate;
}

// "" when the factory knows type; otherwise what is wrong, with the known types.
std::string unknownTypeError(ControllerFactory& factory, const std::string& type, const std::string& type_path) {
  std::vector<std::string> known_types;
  try {
    known_types = factory.types();
  } catch (const std::exception& e) {
    return std::string("listing controller types failed: ") + e.what();
  }
  if (std::find(known_types.begin(), known_types.end(), type) != known_types.end()) return "";
  std::string known;
  for (const auto& t : known_types) known += (known.empty() ? "" : ", ") + t;
  return "unknown controller type '" + type + "' (from '" + type_path + "'); known types: " +
         (known.empty() ? "none" : known) + "; check the spelling or the plugin path";
}

// Fills fallbacks with the controllers names lists (from path), each loaded
// already and claiming nothing that controller `name` (which claimed
// `claimed`) does not; "" on success, otherwise what is wrong.
std::string resolveFallbacks(const std::string& name, const std::string& path, const std::vector<std::string>& names,
                             const std::vector<hardware_interface::InterfaceResources>& claimed,
                             const std::function<detail::ControllerEntry*(const std::string&)>& find,
                             std::vector<detail::ControllerEntry*>& fallbacks) {
  for (const std::string& fallback_name : names) {
    if (fallback_name == name) return "'" + path + "' names the controller itself";
    detail::ControllerEntry* fallback = find(fallback_name);
    if (fallback == nullptr) {
      return "its fallback controller '" + fallback_name + "' (from '" + path + "') is not loaded; load it first";
    }
    for (const auto& held : fallback->info.claimed_resources) {
      for (const std::string& resource : held.resources) {
        const bool also_ours = std::any_of(claimed.begin(), claimed.end(), [&](const auto& ours) {
          return ours.hardware_interface == held.hardware_interface && ours.resources.count(resource) != 0;
        });
        if (!also_ours) {
          return "its fallback controller '" + fallback_name + "' claims '" + resource + "' through " +
                 held.hardware_interface + ", which '" + name +
                 "' does not; a fallback may only take over what its controller holds";
        }
      }
    }
    if (std::find(fallbacks.begin(), fallbacks.end(), fallback) == fallbacks.end()) fallbacks.push_back(fallback);
  }
  return "";
}

}  // namespace

ControllerManager::ParameterLookup ControllerManager::lookupIn(YAML::Node namespace_parameters) {
  return [params = std::move(namespace_parameters)](const std::string& name) -> YAML::Node {
    // Read through a const node: operator[] on a non-const node would insert.
    const YAML::Node& all = params;
    if (!all.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node found = all[name];
    return found.IsDefined() ? found : YAML::Node(YAML::NodeType::Undefined);
  };
}

ControllerManager::ControllerManager(hardware_interface::RobotHW* robot_hw,
                                     std::shared_ptr<ControllerFactory> factory,
                                     ParameterLookup parameters, ControllerContext context_template,
                                     double update_rate_hz)
    : robot_hw_(robot_hw),
      factory_(std::move(factory)),
      parameters_(std::move(parameters)),
      context_template_(std::move(context_template)),
      update_rate_hz_(update_rate_hz) {
  asymmetric_list_fence_ = asymmetric_fence::available();
  // The clock timed updates read (setUpdateTiming), calibrated here, once per
  // process, rather than on the real-time thread.
  loop_clock::prepareCycleClock();
  if (robot_hw_ == nullptr) throw Error("ControllerManager: the RobotHW pointer is null");
  if (!factory_) throw Error("ControllerManager: the controller factory is null");
  if (!parameters_) throw Error("ControllerManager: no parameter lookup given");
  if (!(update_rate_hz_ >= 0.0)) {
    throw ConfigError("ControllerManager: update_rate must be >= 0 Hz (0: no fixed rate), got " +
                      std::to_string(update_rate_hz_));
  }
  context_template_.manager_update_rate_hz = update_rate_hz_;
}

ControllerManager::~ControllerManager() {
  // Controllers go before the factory (member order); nothing is running any
  // more, so no switch or stopping() is needed.
  realtime_lists_[0].clear();
  realtime_lists_[1].clear();
  entries_.clear();
}

ServiceResult ControllerManager::fail(std::string message) const {
  logger().error("{}", message);
  return ServiceResult::failure(std::move(message));
}

detail::ControllerEntry* ControllerManager::findEntry(const std::string& name) const {
  for (const auto& entry : entries_) {
    if (entry->name == name) return entry.get();
  }
  return nullptr;
}

ServiceResult ControllerManager::loadController(const std::string& name) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  const std::string& ns = context_template_.robot_namespace;
  if (name.empty()) return fail("load controller: the controller name is empty");
  if (findEntry(name) != nullptr) {
    return fail("load controller '" + name + "': a controller of that name is already loaded");
  }

  // Parameters and type.
  // reset() rebinds without writing through to a node shared with the lookup;
  // an invalid (zombie) node from a lookup counts as missing.
  YAML::Node params(YAML::NodeType::Undefined);
  try {
    const YAML::Node found = parameters_(name);
    if (found.IsDefined()) params.reset(found);
  } catch (const std::exception& e) {
    return fail("load controller '" + name + "': reading its parameters failed: " + e.what());
  }
  const YAML::Node& const_params = params;
  const std::string type_path = parameterPath(ns, name, "type");
  if (!const_params.IsDefined() || !const_params.IsMap() || !const_params["type"]) {
    return fail("load controller '" + name + "': parameter '" + type_path +
                "' is missing; add 'type: <package>/<Controller>' under '" + name +
                "' in the controller YAML and load it");
  }
  // The manager's own keys, checked before anything is created.
  std::string param_path = parameterPath(ns, name, "");
  param_path.pop_back();  // "<ns>/<name>"
  const params::Parameters view = params::parametersFromYaml(params, std::move(param_path));
  const params::Schema& keys = managerKeysSchema();
  std::string type;
  double requested_rate_hz = 0.0;
  std::vector<std::string> fallback_names;
  try {
    keys.check(view);
    type = keys.text(view, "type");
    requested_rate_hz = keys.number(view, "update_rate");
    fallback_names = keys.textList(view, "fallback_controllers");
  } catch (const std::exception& e) {
    return fail("load controller '" + name + "': " + e.what());
  }
  if (std::string error = unknownTypeError(*factory_, type, type_path); !error.empty()) {
    return fail("load controller '" + name + "': " + error);
  }

  const UpdateRateChoice rate = chooseRateOrWarn(name, update_rate_hz_, requested_rate_hz);

  // Create and initialise, off the real-time thread.
  ControllerPtr controller;
  try {
    controller = factory_->create(type);
  } catch (const std::exception& e) {
    return fail("load controller '" + name + "': creating type '" + type + "' failed: " + e.what());
  }
  if (!controller) {
    return fail("load controller '" + name + "': the factory made no controller of type '" + type + "'");
  }
  ControllerContext context = context_template_;
  context.name = name;
  context.params = view;
  std::vector<hardware_interface::InterfaceResources> claimed;
  try {
    if (!controller->initRequest(robot_hw_, context, claimed)) {
      return fail("load controller '" + name + "' (type '" + type +
                  "'): init returned false; see the controller's messages above");
    }
  } catch (const std::exception& e) {
    return fail("load controller '" + name + "' (type '" + type + "'): init failed: " + e.what());
  } catch (...) {
    return fail("load controller '" + name + "' (type '" + type + "'): init threw an unknown exception");
  }

  // Fallback controllers: loaded already, and taking over nothing this one
  // does not hold, so starting them when it faults can never conflict.
  std::vector<detail::ControllerEntry*> fallbacks;
  const std::string fallback_error =
      resolveFallbacks(name, parameterPath(ns, name, "fallback_controllers"), fallback_names, claimed,
                       [this](const std::string& fallback) { return findEntry(fallback); }, fallbacks);
  if (!fallback_error.empty()) return fail("load controller '" + name + "': " + fallback_error);

  auto entry = std::make_unique<detail::ControllerEntry>();
  entry->name = name;
  entry->type = type;
  entry->controller = std::move(controller);
  entry->info = hardware_interface::ControllerInfo{name, type, claimed};
  entry->rate = rate;
  entry->fallbacks = std::move(fallbacks);

  std::vector<detail::ControllerEntry*> list =
      realtime_lists_[realtime_current_list_.load()];
  list.push_back(entry.get());
  entries_.push_back(std::move(entry));
  publishRealtimeList(std::move(list));
  logger().info("loaded controller '{}' (type '{}')", name, type);
  return ServiceResult::success();
}

ServiceResult ControllerManager::unloadController(const std::string& name) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  return unloadLocked(name);
}

ServiceResult ControllerManager::unloadLocked(const std::string& name_ref) {
  // A copy: callers may pass a reference to the name of the entry destroyed below.
  const std::string name = name_ref;
  finishDoneSwitchLocked();
  detail::ControllerEntry* entry = findEntry(name);
  if (entry == nullptr) {
    return fail("unload controller '" + name + "': no controller of that name is loaded");
  }
  if (entry->controller->isRunning()) {
    return fail("unload controller '" + name +
                "': it is running; stop it first (switch with it in the stop list)");
  }
  for (const auto& other : entries_) {
    if (std::find(other->fallbacks.begin(), other->fallbacks.end(), entry) != other->fallbacks.end()) {
      return fail("unload controller '" + name + "': it is the fallback of '" + other->name + "'; unload '" +
                  other->name + "' first");
    }
  }
  if (switch_phase_.load() != SwitchPhase::idle) {
    return fail("unload controller '" + name +
                "': a controller switch is still waiting for the real-time thread; retry after it");
  }

  std::vector<detail::ControllerEntry*> list = realtime_lists_[realtime_current_list_.load()];
  list.erase(std::remove(list.begin(), list.end(), entry), list.end());
  // After this the real-time thread cannot reach the entry any more.
  publishRealtimeList(std::move(list));

  auto owned = std::find_if(entries_.begin(), entries_.end(),
                            [entry](const auto& e) { return e.get() == entry; });
  std::unique_ptr<detail::ControllerEntry> doomed = std::move(*owned);
  entries_.erase(owned);
  doomed.reset();  // the controller's destructor runs here, on this thread
  logger().info("unloaded controller '{}'", name);
  return ServiceResult::success();
}

void ControllerManager::waitUntilRealtimeLeaves(int list_index) const {
  if (asymmetric_list_fence_) asymmetric_fence::heavy();
  while (realtime_reading_list_.load() == list_index) {
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
}

void ControllerManager::publishRealtimeList(std::vector<detail::ControllerEntry*> list) {
  const int current = realtime_current_list_.load();
  const int spare = 1 - current;
  // The real-time thread only ever picks up the current list, but it may still
  // be inside the update() that read the spare one before the last swap.
  waitUntilRealtimeLeaves(spare);
  realtime_lists_[spare] = std::move(list);
  realtime_current_list_.store(spare);
  // From here on the old list may only be in use by an update() already
  // running; once that finishes nobody reads it.
  waitUntilRealtimeLeaves(current);
}

std::vector<std::pair<std::string, DurationSnapshot>> ControllerManager::updateTimes() {
  std::lock_guard<std::mutex> lock(services_mutex_);
  std::vector<std::pair<std::string, DurationSnapshot>> times;
  times.reserve(entries_.size());
  for (const auto& entry : entries_) times.emplace_back(entry->name, entry->update_time.snapshot());
  return times;
}

std::vector<ControllerSpec> ControllerManager::listControllers() {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  std::vector<ControllerSpec> specs;
  specs.reserve(entries_.size());
  for (const auto& entry : entries_) {
    specs.push_back(ControllerSpec{entry->name, entry->type, entry->controller->state(),
                                   entry->info.claimed_resources, entry->rate.rate_hz,
                                   entry->rate.divisor, entry->last_fault, entry->last_fault_kind});
  }
  return specs;
}

std::vector<std::string> ControllerManager::listControllerTypes() {
  std::lock_guard<std::mutex> lock(services_mutex_);
  std::vector<std::string> types = factory_->types();
  std::sort(types.begin(), types.end());
  return types;
}

ControllerBase* ControllerManager::getController(const std::string& name) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  detail::ControllerEntry* entry = findEntry(name);
  return entry == nullptr ? nullptr : entry->controller.get();
}

ServiceResult ControllerManager::reloadControllerLibraries(bool force_kill, double stop_timeout_s) {
  std::lock_guard<std::mutex> lock(services_mutex_);
  processFaultsLocked();
  finishDoneSwitchLocked();
  if (!entries_.empty()) {
    std::string loaded;
    for (const auto& entry : entries_) loaded += (loaded.empty() ? "" : ", ") + entry->name;
    if (!force_kill) {
      return fail("reload controller libraries: controllers are still loaded (" + loaded +
                  "); unload them first, or reload with force_kill");
    }
    SwitchRequest stop_all;
    stop_all.strictness = SwitchStrictness::STRICT;
    stop_all.timeout_s = stop_timeout_s;
    for (const auto& entry : entries_) {
      if (entry->controller->isRunning()) stop_all.stop_controllers.push_back(entry->name);
    }
    if (!stop_all.stop_controllers.empty()) {
      bool nothing_to_do = false;
      ServiceResult prepared = prepareSwitchLocked(stop_all, &nothing_to_do);
      if (!prepared) return prepared;
      if (!nothing_to_do) {
        ServiceResult stopped = waitForSwitchLocked(stop_timeout_s);
        if (!stopped) return fail("reload controller libraries: " + stopped.message);
      }
    }
    // Unload in reverse load order, as the spawner does.
    while (!entries_.empty()) {
      ServiceResult unloaded = unloadLocked(entries_.back()->name);
      if (!unloaded) return fail("reload controller libraries: " + unloaded.message);
    }
  }
  try {
    factory_->reloadLibraries();
  } catch (const std::exception& e) {
    return fail(std::string("reload controller libraries: ") + e.what());
  }
  logger().info("reloaded controller libraries");
  return ServiceResult::success();
}

std::vector<ControllerFault> ControllerManager::processFaults() {
  std::lock_guard<std::mutex> lock(services_mutex_);
  return processFaultsLocked();
}

std::vector<ControllerFault> ControllerManager::processFaultsLocked() {
  std::vector<ControllerFault> faults;
  for (const auto& entry : entries_) {
    detail::FaultRecord& record = entry->fault;
    if (!record.pending.load(std::memory_order_acquire)) continue;
    std::string reason = toString(record.kind);
    if (record.kind == FaultKind::non_finite_command) {
      const auto& commands = entry->controller->claimedCommands();
      if (record.command_index < commands.size()) {
        const ClaimedCommand& bad = commands[record.command_index];
        reason = "it wrote a non-finite command (" + std::to_string(record.command_value) +
                 ") to '" + bad.resource + "' through " + bad.hardware_interface;
      }
    } else if (record.what[0] != '\0') {
      reason += ": ";
      reason += record.what.data();
    }
    std::string message = "controller '" + entry->name + "' (type '" + entry->type +
                          "') was stopped and marked failed: " + reason +
                          "; its claimed commands were set to safe values (zero effort/velocity, "
                          "hold position)";
    if (record.fallbacks_started) {
      std::string names;
      for (const auto* fallback : entry->fallbacks) names += (names.empty() ? "'" : ", '") + fallback->name + "'";
      message += ", and its fallback controller(s) " + names + " started in the same cycle";
    }
    logger().error("{}", message);
    entry->last_fault = message;
    entry->last_fault_kind = record.kind;
    faults.push_back(ControllerFault{entry->name, record.kind, std::move(message)});
    record.pending.store(false, std::memory_order_release);
  }
  return faults;
}

}  // namespace servoloop::controller_manager
