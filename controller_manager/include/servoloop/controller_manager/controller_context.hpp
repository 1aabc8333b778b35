#pragma once
// What a controller is told about its surroundings when it is initialised.
#include <memory>
#include <string>

#include "servoloop/params/parameters.hpp"

namespace urdf {
class ModelInterface;  // <urdf_model/model.h>: include it to read the robot model
}

namespace servoloop::realtime {
class TopicBus;        // servoloop/realtime/topic_bus.hpp
class ActionRegistry;  // servoloop/realtime/action_registry.hpp
}
namespace servoloop::params {
class ParameterStore;  // servoloop/params/parameter_store.hpp
}

namespace servoloop::controller_manager {

// Handed to ControllerBase::initRequest (non-real-time). The manager fills one
// per controller from its own template: name and params are the controller's,
// the pointers are shared by every controller of the manager.
struct ControllerContext {
  std::string name;              // controller name, e.g. "joint1_position_controller"
  std::string robot_namespace;   // e.g. "/one_DOF_robot"
  params::Parameters params;     // the controller's own parameters (<ns>/<name>), read-only
  realtime::TopicBus* topics = nullptr;    // may be null (tests)
  realtime::ActionRegistry* actions = nullptr;  // where to serve actions; may be null (tests)
  const params::ParameterStore* parameters = nullptr;  // whole store; may be null
  std::shared_ptr<const urdf::ModelInterface> robot_model;  // may be null
  double manager_update_rate_hz = 0.0;  // 0 when the manager runs at no fixed rate
};

}  // namespace servoloop::controller_manager
