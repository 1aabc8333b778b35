#include "servoloop/realtime/action_registry.hpp"

#include <map>

#include "servoloop/core/errors.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::realtime {

struct ActionRegistration::Core {
  struct Entry {
    std::string type;
    std::shared_ptr<ActionServer> server;
  };
  // Held while a goal is sent, so a server is never withdrawn mid-call.
  mutable std::mutex mutex;
  std::map<std::string, Entry> actions;
};

const char* goalStateName(GoalState state) noexcept {
  switch (state) {
    case GoalState::pending: return "PENDING";
    case GoalState::active: return "ACTIVE";
    case GoalState::succeeded: return "SUCCEEDED";
    case GoalState::aborted: return "ABORTED";
    case GoalState::preempted: return "PREEMPTED";
    case GoalState::canceled: return "CANCELED";
    case GoalState::rejected: return "REJECTED";
  }
  return "UNKNOWN";
}

ActionRegistration::ActionRegistration(ActionRegistration&& other) noexcept
    : core_(std::move(other.core_)), name_(std::move(other.name_)) {
  other.name_.clear();
}

ActionRegistration& ActionRegistration::operator=(ActionRegistration&& other) noexcept {
  if (this != &other) {
    reset();
    core_ = std::move(other.core_);
    name_ = std::move(other.name_);
    other.name_.clear();
  }
  return *this;
}

void ActionRegistration::reset() {
  if (name_.empty()) return;
  if (auto core = core_.lock()) {
    std::shared_ptr<ActionServer> server;  // destroyed outside the lock
    {
      std::lock_guard lock(core->mutex);
      auto it = core->actions.find(name_);
      if (it != core->actions.end()) {
        server = std::move(it->second.server);
        core->actions.erase(it);
      }
    }
  }
  name_.clear();
  core_.reset();
}

ActionRegistry::ActionRegistry() : core_(std::make_shared<ActionRegistration::Core>()) {}
ActionRegistry::~ActionRegistry() = default;

ActionRegistration ActionRegistry::add(std::string_view name, std::string_view type,
                                       std::shared_ptr<ActionServer> server) {
  const std::string normalized = TopicBus::normalizeTopicName(name);
  if (!server) throw Error("action '" + normalized + "': no server given");
  std::lock_guard lock(core_->mutex);
  if (core_->actions.count(normalized) != 0) {
    throw Error("action '" + normalized + "' is already served (by " + core_->actions[normalized].type +
                "); give the controller another name");
  }
  core_->actions.emplace(normalized, ActionRegistration::Core::Entry{std::string(type), std::move(server)});
  return ActionRegistration(core_, normalized);
}

std::vector<ActionInfo> ActionRegistry::list() const {
  std::lock_guard lock(core_->mutex);
  std::vector<ActionInfo> infos;
  for (const auto& [name, entry] : core_->actions) infos.push_back({name, entry.type});
  return infos;
}

std::string ActionRegistry::typeOf(std::string_view name) const {
  const std::string normalized = TopicBus::normalizeTopicName(name);
  std::lock_guard lock(core_->mutex);
  const auto it = core_->actions.find(normalized);
  return it == core_->actions.end() ? std::string() : it->second.type;
}

std::shared_ptr<ActionGoal> ActionRegistry::sendGoal(std::string_view name, std::string_view type, const void* goal) {
  const std::string normalized = TopicBus::normalizeTopicName(name);
  std::lock_guard lock(core_->mutex);
  const auto it = core_->actions.find(normalized);
  if (it == core_->actions.end()) {
    std::string names;
    for (const auto& [known, entry] : core_->actions) names += (names.empty() ? "" : ", ") + known;
    throw Error("no action '" + normalized + "' (" +
                (names.empty() ? std::string("this robot serves no action; start a controller that serves one, "
                                             "e.g. a JointTrajectoryController")
                               : "actions are: " + names) +
                ")");
  }
  if (it->second.type != type) {
    throw Error("action '" + normalized + "' is of type " + it->second.type + ", not " + std::string(type) +
                "; send it a " + it->second.type + " goal");
  }
  return it->second.server->sendGoal(goal);
}

}  // namespace servoloop::realtime
