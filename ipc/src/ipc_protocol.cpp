#include "servoloop/ipc/ipc_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "servoloop/core/errors.hpp"

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

std::string requestOpName(const nlohmann::json& request) {
  if (request.is_object()) {
    const auto op = request.find(kIpcOpKey);
    if (op != request.end() && op->is_string()) return op->get<std::string>();
  }
  return "?";
}

std::string describeJsonValue(const nlohmann::json& value) {
  constexpr std::size_t kShown = 80;
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kShown) text = text.substr(0, kShown) + "... (" + describeJsonType(value) + ")";
  return text;
}

void throwBadRequestField(const nlohmann::json& request, std::string_view field, std::string_view expected,
                          const nlohmann::json& given) {
  throw Error(requestOpName(request) + ": '" + std::string(field) + "' must be " + std::string(expected) + ", got " +
              describeJsonValue(given));
}

const nlohmann::json* findRequestField(const nlohmann::json& request, std::string_view field) {
  if (!request.is_object()) return nullptr;
  const auto it = request.find(field);
  if (it == request.end() || it->is_null()) return nullptr;
  return &*it;
}

bool requestBool(const nlohmann::json& request, std::string_view field, bool fallback) {
  const nlohmann::json* value = findRequestField(request, field);
  if (value == nullptr) return fallback;
  if (!value->is_boolean()) throwBadRequestField(request, field, "true or false", *value);
  return value->get<bool>();
}

double requestNumber(const nlohmann::json& request, std::string_view field, double fallback,
                     std::string_view expected) {
  const nlohmann::json* value = findRequestField(request, field);
  if (value == nullptr) return fallback;
  if (!value->is_number()) throwBadRequestField(request, field, expected, *value);
  const double number = value->get<double>();
  if (!std::isfinite(number)) throwBadRequestField(request, field, std::string(expected) + " (finite)", *value);
  return number;
}

std::string requestString(const nlohmann::json& request, std::string_view field, const std::string& fallback) {
  const nlohmann::json* value = findRequestField(request, field);
  if (value == nullptr) return fallback;
  if (!value->is_string()) throwBadRequestField(request, field, "a string", *value);
  return value->get<std::string>();
}

std::string requireRequestString(const nlohmann::json& request, std::string_view field) {
  const nlohmann::json* value = findRequestField(request, field);
  if (value == nullptr) {
    throw Error(requestOpName(request) + ": '" + std::string(field) + "' is required (a non-empty string)");
  }
  if (!value->is_string() || value->get_ref<const std::string&>().empty()) {
    throwBadRequestField(request, field, "a non-empty string", *value);
  }
  return value->get<std::string>();
}

std::uint64_t requireRequestUnsigned(const nlohmann::json& request, std::string_view field,
                                     std::string_view expected) {
  const nlohmann::json* value = findRequestField(request, field);
  if (value == nullptr) {
    throw Error(requestOpName(request) + ": '" + std::string(field) + "' is required (" + std::string(expected) + ")");
  }
  if (!value->is_number_unsigned()) throwBadRequestField(request, field, expected, *value);
  return value->get<std::uint64_t>();
}

std::string describeJsonException(const nlohmann::json& request, const nlohmann::json::exception& error) {
  std::string text = jsonErrorText(error);
  // type_error.302 reads "type must be boolean, but is string".
  const std::string must = "type must be ";
  const std::string but = ", but is ";
  const auto at_must = text.find(must);
  const auto at_but = text.find(but);
  if (at_must != std::string::npos && at_but != std::string::npos && at_but > at_must) {
    const std::string wanted = text.substr(at_must + must.size(), at_but - at_must - must.size());
    const std::string given = text.substr(at_but + but.size());
    text = "a field must be " + wanted + " but is " + given;
  }
  const std::string op = requestOpName(request);
  return op + ": the request has a field of the wrong type or value (" + text +
         "); see docs/ipc_protocol.md for the fields '" + op + "' takes";
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
