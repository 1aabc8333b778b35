#pragma once
// The ControllerFactory of a running node (and of a hand-written main): controllers come from plugin
// libraries (kind "controller") found by a PluginLoader. Non-real-time.
#include <memory>
#include <string>
#include <vector>

#include "servoloop/controller_manager/controller_factory.hpp"
#include "servoloop/plugin/plugin_loader.hpp"

namespace servoloop::node {

class PluginControllerFactory final : public controller_manager::ControllerFactory {
 public:
  // loader must not be null; it is shared with whoever else creates plugins
  // (the node's backends) and kept alive by every controller made here.
  explicit PluginControllerFactory(std::shared_ptr<plugin::PluginLoader> loader);

  // A new controller of a registered controller type; nullptr when no library
  // on the plugin path provides `type` as a controller. Throws servoloop::Error
  // when the type exists under another kind or its constructor throws.
  controller_manager::ControllerPtr create(const std::string& type) override;
  // Every controller type on the plugin path, sorted.
  std::vector<std::string> types() override;
  // Rescans the plugin path (PluginLoader::reload); the manager calls it once
  // no controller of it is loaded. Throws servoloop::Error while other objects
  // from the loader are alive and they would be affected.
  void reloadLibraries() override;

  plugin::PluginLoader& loader() { return *loader_; }

 private:
  std::shared_ptr<plugin::PluginLoader> loader_;
};

}  // namespace servoloop::node
