#pragma once
// Where the manager gets controllers from: the plugin loader in a running node,
// an in-process table in tests and in programs that link controllers directly.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_base.hpp"

namespace servoloop::controller_manager {

// A controller with the deleter of the code that created it (a plugin's
// deleter must run in the plugin's own library).
using ControllerPtr = std::unique_ptr<ControllerBase, std::function<void(ControllerBase*)>>;

class ControllerFactory {
 public:
  virtual ~ControllerFactory() = default;

  // Non-real-time. A new, constructed (not yet initialised) controller of the
  // given type, e.g. "effort_controllers/JointPositionController"; nullptr
  // when the type is unknown. May throw servoloop::Error.
  virtual ControllerPtr create(const std::string& type) = 0;

  // Non-real-time. Every type create() knows.
  virtual std::vector<std::string> types() = 0;

  // Non-real-time. Called by ControllerManager::reloadControllerLibraries once
  // no controller is loaded any more: re-open the libraries the types come
  // from. Throws servoloop::Error when that fails. Default: nothing to reload.
  virtual void reloadLibraries() {}
};

// A factory whose types are registered in process, by C++ type or by a
// creation function. Used by tests and by programs that link controllers in.
class InProcessControllerFactory : public ControllerFactory {
 public:
  using Creator = std::function<ControllerPtr()>;

  void add(const std::string& type, Creator creator) { creators_[type] = std::move(creator); }

  template <class ControllerT>
  void add(const std::string& type) {
    add(type, [] {
      return ControllerPtr(new ControllerT(), [](ControllerBase* c) { delete c; });
    });
  }

  ControllerPtr create(const std::string& type) override {
    auto it = creators_.find(type);
    return it == creators_.end() ? ControllerPtr() : it->second();
  }

  std::vector<std::string> types() override {
    std::vector<std::string> names;
    names.reserve(creators_.size());
    for (const auto& [name, creator] : creators_) names.push_back(name);
    return names;
  }

 private:
  std::map<std::string, Creator> creators_;
};

}  // namespace servoloop::controller_manager
