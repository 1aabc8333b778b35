#include "servoloop/ipc/ipc_protocol.hpp"

#include <algorithm>
#include <string>

namespace servoloop::ipc {

namespace {

// The message a json::exception carries, without its "[json.exception.x.y] " tag.
std::string jsonErrorText(const nlohmann::json::exception& error) {
  std::string text = error.what();
  if (!text.empty() && text.front() == '[') {
    const auto end = text.find("] ");
    if (end != std::string::npos) text.erase(0, end + 2);
  }
  return text;
}

// How deep the arrays and objects of a JSON text nest (brackets inside
// strings do not count); a cheap scan that needs no parse.
int jsonNestingDepth(std::string_view text) {
  int depth = 0;
  int deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

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

IpcRequestCheck parseIpcRequest(std::string_view line) {
  IpcRequestCheck check;
  const auto reject = [&](const nlohmann::json& id, const std::string& message) {
    check.error = makeIpcErrorReply(id, message);
    return check;
  };
  const int depth = jsonNestingDepth(line);
  if (depth > kIpcMaxRequestDepth) {
    return reject(nullptr, "request nests arrays/objects " + std::to_string(depth) + " deep; the limit is " +
                               std::to_string(kIpcMaxRequestDepth));
  }
  nlohmann::json request;
  try {
    request = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception& error) {  // syntax, and numbers no double can hold (1e400)
    return reject(nullptr, "request is not valid JSON: " + jsonErrorText(error));
  }
  if (!request.is_object()) {
    return reject(nullptr, "request must be a JSON object like {\"id\": 1, \"op\": \"...\"}, got " +
                               describeJsonType(request));
  }
  const auto id_field = request.find(kIpcIdKey);
  const nlohmann::json id = id_field != request.end() ? *id_field : nlohmann::json();
  if (!id.is_null() && !id.is_number_integer()) {
    return reject(id, "request \"id\" must be an integer, got " + describeJsonType(id));
  }
  const auto op = request.find(kIpcOpKey);
  if (op == request.end()) return reject(id, "request has no \"op\" field naming the operation");
  if (!op->is_string()) return reject(id, "request \"op\" must be a string, got " + describeJsonType(*op));
  check.ok = true;
  check.request = std::move(request);
  return check;
}

}  // namespace servoloop::ipc
