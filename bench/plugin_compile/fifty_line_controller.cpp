// A typical small out-of-tree controller, used to measure how long a plugin
// author waits for one compile (docs/benchmarks.md, "Plugin compile time"):
// one joint, a proportional law on a commanded position, a command topic.
#include <string>

#include <servoloop/controller_manager/controller.hpp>
#include <servoloop/hardware_interface/joint_interfaces.hpp>
#include <servoloop/plugin/plugin_register.hpp>
#include <servoloop/realtime/messages.hpp>
#include <servoloop/realtime/realtime_subscriber.hpp>
#include <servoloop/realtime/topic_bus.hpp>

namespace bench_controllers {

namespace cm = servoloop::controller_manager;
namespace hi = servoloop::hardware_interface;

class ProportionalController : public cm::Controller<hi::EffortJointInterface> {
 public:
  bool init(hi::EffortJointInterface* hw, const cm::ControllerContext& context) override {
    joint_ = hw->getHandle(context.params.get<std::string>("joint"));
    gain_ = context.params.get<double>("gain", 10.0);
    if (context.topics != nullptr) {
      command_ = context.topics->commandInput<servoloop::std_msgs::Float64>(
          context.robot_namespace + "/" + context.name + "/command");
    }
    return true;
  }

  void starting(const servoloop::Time& /*time*/) override { setpoint_ = joint_.getPosition(); }

  servoloop::ReturnType update(const servoloop::Time& /*time*/,
                               const servoloop::Duration& /*period*/) override {
    if (const auto* command = command_.latest()) setpoint_ = command->data;
    joint_.setCommand(gain_ * (setpoint_ - joint_.getPosition()));
    return servoloop::ReturnType::ok;
  }

 private:
  hi::JointHandle joint_;
  double gain_ = 0.0;
  double setpoint_ = 0.0;
  servoloop::realtime::RealtimeSubscriber<servoloop::std_msgs::Float64> command_;
};

}  // namespace bench_controllers

SERVOLOOP_REGISTER_PLUGIN(bench_controllers::ProportionalController,
                          servoloop::controller_manager::ControllerBase,
                          "bench_controllers/ProportionalController")
