// `topic pub` text read as YAML/JSON, then converted to every message type
// servoloop knows and printed back as rostopic text.
#include "fuzz_common.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/realtime/messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = servoloop::fuzz::text(data, size);
  return servoloop::fuzz::refusalsAllowed([&] {
    const nlohmann::json message = servoloop::node::parseMessageText(text, "fuzz");
    for (const std::string& type : servoloop::node::knownMessageTypes()) {
      servoloop::fuzz::refusalsAllowed([&] { servoloop::node::messageToText(type, message); });
    }
    servoloop::fuzz::refusalsAllowed([&] { servoloop::node::messageFromJson<servoloop::std_msgs::Float64>(message); });
    servoloop::fuzz::refusalsAllowed(
        [&] { servoloop::node::messageFromJson<servoloop::std_msgs::Float64MultiArray>(message); });
    servoloop::fuzz::refusalsAllowed(
        [&] { servoloop::node::messageFromJson<servoloop::sensor_msgs::JointState>(message); });
    servoloop::fuzz::refusalsAllowed([&] { servoloop::node::messageFromJson<servoloop::nav_msgs::Odometry>(message); });
  });
}
