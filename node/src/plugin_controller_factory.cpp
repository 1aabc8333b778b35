#include "servoloop/node/plugin_controller_factory.hpp"

#include "servoloop/core/errors.hpp"

namespace servoloop::node {

PluginControllerFactory::PluginControllerFactory(std::shared_ptr<plugin::PluginLoader> loader)
    : loader_(std::move(loader)) {
  if (!loader_) throw Error("PluginControllerFactory: the plugin loader must not be null");
}

controller_manager::ControllerPtr PluginControllerFactory::create(const std::string& type) {
  bool known_controller = false;
  for (const plugin::PluginTypeInfo& info : loader_->listTypes(controller_manager::ControllerBase::kPluginKind)) {
    known_controller |= (info.type == type);
  }
  if (!known_controller) return controller_manager::ControllerPtr();
  plugin::PluginPtr<controller_manager::ControllerBase> created = loader_->create<controller_manager::ControllerBase>(type);
  // The plugin's deleter (its library's delete, then the library reference)
  // travels with the controller.
  plugin::PluginDeleter deleter = created.get_deleter();
  return controller_manager::ControllerPtr(created.release(), [deleter](controller_manager::ControllerBase* controller) { deleter(controller); });
}

std::vector<std::string> PluginControllerFactory::types() {
  std::vector<std::string> names;
  for (const plugin::PluginTypeInfo& info : loader_->listTypes(controller_manager::ControllerBase::kPluginKind)) names.push_back(info.type);
  return names;
}

void PluginControllerFactory::reloadLibraries() {
  // Backends made by the same loader stay alive while the node runs: force
  // keeps their libraries mapped and rescans everything else.
  loader_->reload(/*force=*/true);
}

}  // namespace servoloop::node
