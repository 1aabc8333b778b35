#pragma once
// The wire protocol between a running servoloop node (`servoloop launch`) and
// the command line (`servoloop spawner`, `control`, `topic`, `param`,
// `spawn-model`). The full description with examples is docs/ipc_protocol.md.
//
// Transport: one Unix stream socket per node, `<run dir>/<node>.sock` (see
// ipc_socket_path.hpp). Messages are newline-delimited JSON: one JSON value
// per line, UTF-8, terminated by '\n'. A line may not exceed
// kIpcMaxRequestLineBytes.
//
// Request (client -> node), a JSON object:
//   {"id": <int>, "op": "<string>", ...op-specific arguments}
// Reply (node -> client), exactly one per request, carrying the same id:
//   {"id": <same>, "ok": true, ...op-specific results}
//   {"id": <same>, "ok": false, "error": "<one clear line>"}
// Replies may arrive in a different order than the requests when a handler
// answers later (see IpcServer::Handler); match them by id. A request the node
// could not parse is answered with "id": null.
//
// Stream message (node -> client), pushed unsolicited to a connection that
// subscribed to something (e.g. `topic echo`); it has a "stream" key and no
// "id":
//   {"stream": "<name>", ...payload}
//
// Connection rules the node enforces:
//   - a line that is not JSON (a number no double holds, such as 1e400,
//     included), nests deeper than kIpcMaxRequestDepth, is not an object, or
//     lacks a string "op" gets an error reply; the connection stays open;
//   - a line over kIpcMaxRequestLineBytes (or that much data without a
//     newline) gets an error reply, then the node closes the connection;
//   - a partial line followed by end-of-file is discarded without a reply;
//     the complete requests before it are all answered (deferred replies
//     included) before the connection closes;
//   - a client that does not read what the node sends, until more than
//     kIpcMaxPendingOutputBytes wait for it, is disconnected.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace servoloop::ipc {

// Longest request line the node accepts, in bytes, not counting the '\n'.
inline constexpr std::size_t kIpcMaxRequestLineBytes = std::size_t{1} << 20;  // 1 MiB
// A request whose arrays and objects nest deeper than this is refused before
// it is parsed (no servoloop message nests more than a few levels).
inline constexpr int kIpcMaxRequestDepth = 64;

// Most bytes the node keeps queued for one connection that is not reading.
inline constexpr std::size_t kIpcMaxPendingOutputBytes = std::size_t{8} << 20;  // 8 MiB

// Longest message line the client accepts from the node, in bytes.
inline constexpr std::size_t kIpcMaxReplyLineBytes = std::size_t{64} << 20;  // 64 MiB

// Field names, spelled once.
inline constexpr std::string_view kIpcIdKey = "id";
inline constexpr std::string_view kIpcOpKey = "op";
inline constexpr std::string_view kIpcOkKey = "ok";
inline constexpr std::string_view kIpcErrorKey = "error";
inline constexpr std::string_view kIpcStreamKey = "stream";

// {"id": id, "ok": true} plus the fields of `results` (an object or null).
nlohmann::json makeIpcOkReply(const nlohmann::json& id, const nlohmann::json& results = nullptr);

// {"id": id, "ok": false, "error": message}; line breaks in `message` become spaces
// so the error stays one line on the client's terminal.
nlohmann::json makeIpcErrorReply(const nlohmann::json& id, std::string_view message);

// {"stream": name} plus the fields of `payload` (an object or null).
nlohmann::json makeIpcStreamMessage(std::string_view stream_name,
                                    const nlohmann::json& payload = nullptr);

// One wire line: compact JSON followed by '\n'. Invalid UTF-8 in strings is
// replaced rather than thrown about, so a bad byte cannot kill a reply.
std::string encodeIpcLine(const nlohmann::json& message);

// The JSON type name as a user would say it ("an array", "a number", ...).
std::string describeJsonType(const nlohmann::json& value);

// --- Reading a request's fields ------------------------------------------------
// Every field a handler reads goes through these: a field of the wrong type
// throws servoloop::Error naming the request, the field, what it must be and
// the value given, e.g.
//   control.switch: 'timeout' must be a number of seconds, got "soon"
// never nlohmann's "[json.exception.type_error.302] type must be ...".
// `expected` says what the field must be ("true or false", "a number of
// seconds"); a missing or null field gives the fallback (optional fields) or
// throws "... is required" (required ones).

// The request's op, for messages ("?" when it has none).
std::string requestOpName(const nlohmann::json& request);

// A value as a message shows it: its JSON text, cut short past ~80 characters.
std::string describeJsonValue(const nlohmann::json& value);

// "<op>: '<field>' must be <expected>, got <value>", thrown as servoloop::Error.
[[noreturn]] void throwBadRequestField(const nlohmann::json& request, std::string_view field,
                                       std::string_view expected, const nlohmann::json& given);

// The field, or nullptr when it is absent or null.
const nlohmann::json* findRequestField(const nlohmann::json& request, std::string_view field);

bool requestBool(const nlohmann::json& request, std::string_view field, bool fallback);
// A finite number (integers included); `expected` as in "a number of seconds".
double requestNumber(const nlohmann::json& request, std::string_view field, double fallback,
                     std::string_view expected = "a number");
std::string requestString(const nlohmann::json& request, std::string_view field, const std::string& fallback);
// A string that is present and not empty.
std::string requireRequestString(const nlohmann::json& request, std::string_view field);
// A whole number >= 0 that is present.
std::uint64_t requireRequestUnsigned(const nlohmann::json& request, std::string_view field,
                                     std::string_view expected = "a whole number >= 0");

// The last resort of a dispatcher: a json::exception a handler let through,
// as one message in the style above instead of nlohmann's raw text, e.g.
//   control.stats: a field of the request has the wrong type (a boolean was expected, a string was given); ...
std::string describeJsonException(const nlohmann::json& request, const nlohmann::json::exception& error);

// A request line checked as the node checks it before any handler sees it:
// ok, the request (an object with a string "op" and an integer or absent
// "id"); otherwise `error` is the reply to send (with the request's id when
// it could be read). Never throws, whatever the line holds.
struct IpcRequestCheck {
  bool ok = false;
  nlohmann::json request;
  nlohmann::json error;
};
IpcRequestCheck parseIpcRequest(std::string_view line);

}  // namespace servoloop::ipc
