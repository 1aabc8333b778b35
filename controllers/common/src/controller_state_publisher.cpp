#include "servoloop/controllers/common/controller_state_publisher.hpp"

#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::controllers {

void ControllerStatePublisher::advertise(servoloop::realtime::TopicBus* bus, const std::string& topic) {
  if (bus == nullptr) return;
  publisher_ = bus->advertise<Message>(topic);
}

}  // namespace servoloop::controllers
