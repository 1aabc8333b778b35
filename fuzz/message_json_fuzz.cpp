// `topic pub` text read as YAML/JSON, then read as every message type
// servoloop knows (and checked, and flattened to CSV) and printed back as
// rostopic text.
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
    for (const std::string& type : servoloop::node::knownMessageTypes()) {
      servoloop::fuzz::refusalsAllowed([&] {
        const nlohmann::json normalized = servoloop::node::normalizeMessage(type, message);
        servoloop::node::requireFiniteCommand(type, normalized);
        servoloop::node::csvRow(type, servoloop::Time(0.0), normalized);
      });
    }
  });
}
