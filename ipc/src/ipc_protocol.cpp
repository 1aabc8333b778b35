#include "servoloop/ipc/ipc_protocol.hpp"

#include <algorithm>

namespace servoloop::ipc {

namespace {

void mergeFields(nlohmann::json& into, const nlohmann::json& fields) {
  if (!fields.is_object()) return;
  for (const auto& [key, value] : fields.items()) into[key] = value;
}

}  // namespace

nlohmann::json makeIpcOkReply(const nlohmann::json& id, const nlohmann::json& results) {
  nlohmann::json reply = nlohmann::json::object();
  mergeFields(reply, results);
  reply[kIpcIdKey] = id;
  reply[kIpcOkKey] = true;
  return reply;
}

nlohmann::json makeIpcErrorReply(const nlohmann::json& id, std::string_view message) {
  std::string one_line(message);
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  std::replace(one_line.begin(), one_line.end(), '\r', ' ');
  return nlohmann::json{{kIpcIdKey, id}, {kIpcOkKey, false}, {kIpcErrorKey, one_line}};
}

nlohmann::json makeIpcStreamMessage(std::string_view stream_name, const nlohmann::json& payload) {
  nlohmann::json message = nlohmann::json::object();
  mergeFields(message, payload);
  message[kIpcStreamKey] = stream_name;
  return message;
}

std::string encodeIpcLine(const nlohmann::json& message) {
  std::string line = message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  line.push_back('\n');
  return line;
}

std::string describeJsonType(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: return "an integer";
    case nlohmann::json::value_t::number_float: return "a floating-point number";
    case nlohmann::json::value_t::binary: return "binary data";
    case nlohmann::json::value_t::discarded: return "a discarded value";
  }
  return "an unknown JSON type";
}

}  // namespace servoloop::ipc
