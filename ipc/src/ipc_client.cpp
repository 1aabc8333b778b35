#include "servoloop/ipc/ipc_client.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include <poll.h>
#include <sys/socket.h>

#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::ipc {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::chrono::milliseconds kBusyRetryInterval{10};
constexpr std::chrono::milliseconds kWaitForNodeInterval{50};

std::string secondsText(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g s", seconds);
  return text;
}

std::string noNodeMessage(const std::string& node_name, const std::filesystem::path& socket_path) {
  return "no servoloop node is running for namespace '" + node_name + "' (looked for " +
         socket_path.native() + "); start one with `servoloop launch <launch file>`";
}

// Milliseconds until `deadline` for poll(): -1 for never, at least 0.
int pollTimeoutUntil(Clock::time_point deadline) {
  if (deadline == Clock::time_point::max()) return -1;
  const auto remaining =
      std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(remaining, 0, 60'000));
}

}  // namespace

IpcClient::Deadline IpcClient::deadlineAfter(double timeout_s) {
  if (!(timeout_s > 0.0) || !std::isfinite(timeout_s) || timeout_s > 1e9) return Deadline::max();
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(timeout_s));
}

IpcClient IpcClient::connectToNode(std::string_view node_name, double timeout_s) {
  IpcClient client;
  client.connect(socketPathFor(node_name), timeout_s);
  return client;
}

void IpcClient::connect(const std::filesystem::path& socket_path, double timeout_s) {
  close();
  const std::string node_name = nodeNameForSocketPath(socket_path);
  // A socket in a directory others can write to could be anybody's.
  if (!checkPrivateDirectoryIfPresent(socket_path.parent_path().empty() ? std::filesystem::path(".")
                                                                        : socket_path.parent_path())) {
    throw Error(noNodeMessage(node_name, socket_path));
  }
  const Deadline deadline = deadlineAfter(timeout_s);
  IpcFd fd;
  while (true) {
    switch (tryConnectUnixSocket(socket_path, fd)) {
      case IpcConnectResult::kConnected:
        fd_ = std::move(fd);
        socket_path_ = socket_path;
        node_name_ = node_name;
        return;
      case IpcConnectResult::kNoListener:
        throw Error(noNodeMessage(node_name, socket_path));
      case IpcConnectResult::kPermissionDenied:
        throw Error("permission denied connecting to the servoloop node for namespace '" + node_name +
                    "' (" + socket_path.native() + "): it belongs to another user");
      case IpcConnectResult::kBusy:
        if (Clock::now() >= deadline) {
          throw Error("the servoloop node for namespace '" + node_name +
                      "' did not accept a connection within " + secondsText(timeout_s) + " (" +
                      socket_path.native() + "); it may be overloaded or stuck");
        }
        std::this_thread::sleep_for(kBusyRetryInterval);
        break;
    }
  }
}

void IpcClient::close() {
  fd_.reset();
  input_.clear();
  input_scanned_ = 0;
  streams_.clear();
}

void IpcClient::failDisconnected(std::string_view waiting_for) {
  std::string message = "the servoloop node for namespace '" + node_name_ + "' (" +
                        socket_path_.native() + ") closed the connection while " +
                        std::string(waiting_for) + "; it may have stopped";
  if (!last_node_error_.empty()) message += ": it said: " + last_node_error_;
  close();
  throw Error(message);
}

void IpcClient::sendAll(const std::string& line, Deadline deadline, std::string_view op) {
  std::size_t sent = 0;
  while (sent < line.size()) {
    const ssize_t written =
        ::send(fd_.get(), line.data() + sent, line.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (written > 0) {
      sent += static_cast<std::size_t>(written);
      continue;
    }
    if (written < 0 && errno == EINTR) continue;
    if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd writable{fd_.get(), POLLOUT, 0};
      const int ready = ::poll(&writable, 1, pollTimeoutUntil(deadline));
      if (ready == 0) {
        throw Error("timed out sending request '" + std::string(op) + "' to the servoloop node for namespace '" +
                    node_name_ + "' (" + socket_path_.native() + "); it is not reading requests");
      }
      continue;
    }
    failDisconnected("sending request '" + std::string(op) + "'");
  }
}

std::optional<nlohmann::json> IpcClient::readMessage(Deadline deadline, std::string_view waiting_for) {
  while (true) {
    const std::size_t newline = input_.find('\n', input_scanned_);
    if (newline != std::string::npos) {
      const std::string line = input_.substr(0, newline);
      input_.erase(0, newline + 1);
      input_scanned_ = 0;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      try {
        return nlohmann::json::parse(line);
      } catch (const nlohmann::json::exception& error) {
        close();
        throw Error("the servoloop node for namespace '" + node_name_ + "' sent a malformed message (" +
                    error.what() + "); is " + socket_path_.native() + " really a servoloop node?");
      }
    }
    input_scanned_ = input_.size();
    if (input_.size() > kIpcMaxReplyLineBytes) {
      close();
      throw Error("the servoloop node for namespace '" + node_name_ + "' sent a message over " +
                  std::to_string(kIpcMaxReplyLineBytes) + " bytes; closing the connection");
    }

    pollfd readable{fd_.get(), POLLIN, 0};
    const int ready = ::poll(&readable, 1, pollTimeoutUntil(deadline));
    if (ready < 0 && errno != EINTR) failDisconnected(waiting_for);
    if (ready == 0) return std::nullopt;
    if (ready < 0) continue;

    char buffer[64 * 1024];
    const ssize_t received = ::recv(fd_.get(), buffer, sizeof(buffer), MSG_DONTWAIT);
    if (received > 0) {
      input_.append(buffer, static_cast<std::size_t>(received));
    } else if (received == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      failDisconnected(waiting_for);
    }
  }
}

nlohmann::json IpcClient::request(nlohmann::json request, double timeout_s) {
  if (!request.is_object() || !request.contains(kIpcOpKey) || !request[kIpcOpKey].is_string()) {
    throw Error("IPC request must be a JSON object with a string \"op\", got: " + request.dump());
  }
  const std::string op = request[kIpcOpKey].get<std::string>();
  if (!isConnected()) {
    throw Error("cannot send request '" + op + "': not connected to a servoloop node");
  }
  const std::int64_t id = next_id_++;
  request[kIpcIdKey] = id;
  const std::string line = encodeIpcLine(request);
  if (line.size() - 1 > kIpcMaxRequestLineBytes) {
    throw Error("request '" + op + "' is " + std::to_string(line.size() - 1) +
                " bytes of JSON, over the node's limit of " + std::to_string(kIpcMaxRequestLineBytes) +
                " bytes (1 MiB)");
  }

  const Deadline deadline = deadlineAfter(timeout_s);
  sendAll(line, deadline, op);
  const std::string waiting_for = "waiting for the reply to '" + op + "'";
  while (true) {
    std::optional<nlohmann::json> message = readMessage(deadline, waiting_for);
    if (!message) {
      throw Error("the servoloop node for namespace '" + node_name_ + "' did not answer '" + op +
                  "' within " + secondsText(timeout_s) + " (" + socket_path_.native() + ")");
    }
    if (!message->is_object()) continue;
    if (message->contains(kIpcStreamKey) && !message->contains(kIpcIdKey)) {
      streams_.push_back(std::move(*message));
      continue;
    }
    const auto reply_id = message->find(kIpcIdKey);
    if (reply_id != message->end() && *reply_id == id) return std::move(*message);
    // "id": null is the node's answer to a line it could not take as a request;
    // the only line in flight that it can be about is ours.
    if (reply_id != message->end() && reply_id->is_null()) return std::move(*message);
    // Anything else is the late reply to a request that timed out: drop it.
  }
}

nlohmann::json IpcClient::call(std::string_view op, const nlohmann::json& args, double timeout_s) {
  nlohmann::json message = args.is_object() ? args : nlohmann::json::object();
  message[kIpcOpKey] = op;
  nlohmann::json reply = request(std::move(message), timeout_s);
  if (reply.value(kIpcOkKey, false) != true) {
    const auto error = reply.find(kIpcErrorKey);
    throw Error(error != reply.end() && error->is_string()
                    ? error->get<std::string>()
                    : "request '" + std::string(op) + "' failed without an error message");
  }
  return reply;
}

std::optional<nlohmann::json> IpcClient::readStream(double timeout_s) {
  if (!streams_.empty()) {
    nlohmann::json message = std::move(streams_.front());
    streams_.pop_front();
    return message;
  }
  if (!isConnected()) throw Error("cannot read stream messages: not connected to a servoloop node");
  const Deadline deadline = deadlineAfter(timeout_s);
  while (true) {
    std::optional<nlohmann::json> message = readMessage(deadline, "waiting for stream messages");
    if (!message) return std::nullopt;
    if (message->is_object() && message->contains(kIpcStreamKey) && !message->contains(kIpcIdKey)) {
      return message;
    }
    // A node error outside any request (e.g. "too many clients") explains a
    // disconnect that may follow; other replies are late and dropped.
    if (message->is_object() && message->contains(kIpcIdKey) && (*message)[kIpcIdKey].is_null()) {
      last_node_error_ = message->value(kIpcErrorKey, std::string());
    }
  }
}

bool waitForSocket(const std::filesystem::path& socket_path, double timeout_s) {
  const Clock::time_point deadline =
      timeout_s > 0.0 && std::isfinite(timeout_s)
          ? Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s))
          : Clock::time_point::max();
  const std::filesystem::path directory =
      socket_path.parent_path().empty() ? std::filesystem::path(".") : socket_path.parent_path();
  while (true) {
    if (checkPrivateDirectoryIfPresent(directory)) {
      IpcFd probe;
      const IpcConnectResult result = tryConnectUnixSocket(socket_path, probe);
      if (result == IpcConnectResult::kConnected) return true;
      if (result == IpcConnectResult::kPermissionDenied) {
        throw Error("permission denied connecting to the servoloop node for namespace '" +
                    nodeNameForSocketPath(socket_path) + "' (" + socket_path.native() +
                    "): it belongs to another user");
      }
    }
    if (Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(kWaitForNodeInterval);
  }
}

bool waitForNode(std::string_view node_name, double timeout_s) {
  return waitForSocket(socketPathFor(node_name), timeout_s);
}

}  // namespace servoloop::ipc
