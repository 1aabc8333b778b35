#pragma once
// A message of a type known only at run time: what untyped subscribers
// (TopicBus::subscribeAny) receive and what TopicBus::publishView takes. The
// node's JSON, text and CSV forms are built on it (servoloop/node/message_json.hpp).
#include <functional>
#include <string_view>

#include "servoloop/core/time.hpp"

namespace servoloop::realtime {

struct MessageView {
  std::string_view type;        // the message's kTypeName, e.g. "std_msgs/Float64"
  const void* data = nullptr;   // points to a message of that type

  // The message as Msg; nullptr when it is of another type.
  template <class Msg>
  const Msg* as() const noexcept {
    return type == Msg::kTypeName ? static_cast<const Msg*>(data) : nullptr;
  }
};

// A subscriber for any message type, with the time it was published
// (TopicBus::now() then). Non-real-time; runs on the delivery thread.
using AnyCallback = std::function<void(Time stamp, const MessageView& msg)>;

}  // namespace servoloop::realtime
