#include "servoloop/ipc/ipc_server.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::ipc {

namespace {

using Clock = std::chrono::steady_clock;

// How long a closing connection may keep unsent output before it is closed anyway.
constexpr std::chrono::milliseconds kCloseGracePeriod{1000};
// How long a closing connection waits for the replies its handlers deferred
// (a controller switch waits for the control loop; see kMaxSwitchWait_s).
constexpr std::chrono::milliseconds kDeferredReplyGracePeriod{60000};
// How long a closing connection whose replies are written keeps reading (and
// dropping) what its client still sends, waiting for the client to close.
constexpr std::chrono::milliseconds kLingerPeriod{2000};
// After accept() runs out of file descriptors, the listening socket stays
// readable; pause accepting instead of spinning.
constexpr std::chrono::milliseconds kAcceptPauseOnExhaustion{100};
constexpr std::size_t kReadChunkBytes = 64 * 1024;

std::string errnoText() { return std::strerror(errno); }

}  // namespace

IpcServer::IpcServer(std::filesystem::path socket_path, Handler handler)
    : socket_path_(std::move(socket_path)),
      lock_path_(std::filesystem::path(socket_path_).replace_extension(".lock")),
      handler_(std::move(handler)) {
  if (!handler_) throw Error("IpcServer for '" + socket_path_.native() + "' needs a request handler");
}

IpcServer::~IpcServer() { stop(); }

IpcServerStats IpcServer::stats() const {
  IpcServerStats stats;
  stats.connections_accepted = connections_accepted_.load();
  stats.requests_handled = requests_handled_.load();
  stats.requests_rejected = requests_rejected_.load();
  stats.clients_dropped_slow = clients_dropped_slow_.load();
  stats.clients_dropped_oversized = clients_dropped_oversized_.load();
  return stats;
}

void IpcServer::start() {
  std::lock_guard<std::mutex> lifecycle(lifecycle_mutex_);
  if (running_.load()) return;
  const std::string node_name = nodeNameForSocketPath(socket_path_);
  const sockaddr_un address = makeUnixAddress(socket_path_);  // checks the length first
  ensurePrivateDirectory(socket_path_.parent_path().empty() ? std::filesystem::path(".")
                                                            : socket_path_.parent_path());

  // The lock file, not the socket file, decides who owns the name: two nodes
  // starting at once could both see a stale socket and both replace it.
  IpcFd lock_fd(::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600));
  if (!lock_fd.valid()) {
    throw Error("cannot open IPC lock file '" + lock_path_.native() + "': " + errnoText());
  }
  if (::flock(lock_fd.get(), LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK) {
      throw Error("a servoloop node is already running for namespace '" + node_name + "' (socket " +
                  socket_path_.native() + "); stop it first, or launch this one under another namespace");
    }
    throw Error("cannot lock IPC lock file '" + lock_path_.native() + "': " + errnoText());
  }

  struct stat existing {};
  if (::lstat(socket_path_.c_str(), &existing) == 0) {
    if (!S_ISSOCK(existing.st_mode)) {
      throw Error("'" + socket_path_.native() + "' exists and is not a socket; refusing to replace it: "
                  "remove it if it is not needed");
    }
    IpcFd probe;
    if (tryConnectUnixSocket(socket_path_, probe) == IpcConnectResult::kConnected) {
      throw Error("a process is already listening on '" + socket_path_.native() +
                  "' without holding its lock file; stop it first");
    }
    logger().info("replacing stale IPC socket '{}' left by a node that is no longer running",
                  socket_path_.native());
    if (::unlink(socket_path_.c_str()) != 0 && errno != ENOENT) {
      throw Error("cannot remove stale IPC socket '" + socket_path_.native() + "': " + errnoText());
    }
  }

  IpcFd listen_fd(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!listen_fd.valid()) throw Error("cannot create the IPC socket: " + errnoText());
  if (::bind(listen_fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    throw Error("cannot bind IPC socket '" + socket_path_.native() + "': " + errnoText());
  }
  struct stat bound {};
  ::lstat(socket_path_.c_str(), &bound);
  if (::listen(listen_fd.get(), SOMAXCONN) != 0) {
    ::unlink(socket_path_.c_str());
    throw Error("cannot listen on IPC socket '" + socket_path_.native() + "': " + errnoText());
  }
  IpcFd wake_fd(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK));
  if (!wake_fd.valid()) {
    ::unlink(socket_path_.c_str());
    throw Error("cannot create the IPC wake-up eventfd: " + errnoText());
  }

  lock_fd_ = std::move(lock_fd);
  listen_fd_ = std::move(listen_fd);
  wake_fd_ = std::move(wake_fd);
  socket_inode_ = bound.st_ino;
  stop_requested_.store(false);
  running_.store(true);
  service_thread_ = std::thread([this] { serviceLoop(); });
  logger().debug("IPC server for '{}' listening on {}", node_name, socket_path_.native());
}

void IpcServer::stop() {
  if (std::this_thread::get_id() == service_thread_.get_id()) {
    throw Error("IpcServer::stop() was called from a request handler or close callback of '" +
                socket_path_.native() + "'; it would wait for itself: stop the server from another thread");
  }
  std::lock_guard<std::mutex> lifecycle(lifecycle_mutex_);
  if (!running_.load()) return;
  stop_requested_.store(true);
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t ignored = ::write(wake_fd_.get(), &one, sizeof(one));
  if (service_thread_.joinable()) service_thread_.join();

  // Connections must be closed before the eventfd they wake goes away.
  for (auto& connection : connections_) closeConnection(*connection);
  connections_.clear();
  connection_count_.store(0);
  releaseSocket();
  wake_fd_.reset();
  running_.store(false);
}

void IpcServer::releaseSocket() {
  listen_fd_.reset();
  // Remove the socket file only if it is still the one we bound.
  struct stat current {};
  if (::lstat(socket_path_.c_str(), &current) == 0 && current.st_ino == socket_inode_) {
    ::unlink(socket_path_.c_str());
  }
  // The lock file stays: removing it while others may have it open would let
  // two nodes each lock a different file of the same name.
  lock_fd_.reset();
}

void IpcServer::closeConnection(IpcConnection& connection) {
  for (auto& callback : connection.closeNow()) {
    try {
      callback();
    } catch (const std::exception& error) {
      logger().warn("IPC client {}: close callback threw: {}", connection.id(), error.what());
    } catch (...) {
      logger().warn("IPC client {}: close callback threw a non-standard exception", connection.id());
    }
  }
}

void IpcServer::serviceLoop() {
  std::vector<pollfd> poll_fds;
  std::vector<std::shared_ptr<IpcConnection>> polled;
  while (!stop_requested_.load()) {
    const Clock::time_point next_deadline = reapConnections();
    const Clock::time_point now = Clock::now();

    // Outline: [wake eventfd] [listening socket unless paused] [one per connection].
    poll_fds.clear();
    polled.clear();
    poll_fds.push_back({wake_fd_.get(), POLLIN, 0});
    const bool accepting = now >= accept_paused_until_;
    poll_fds.push_back({accepting ? listen_fd_.get() : -1, POLLIN, 0});
    for (const auto& connection : connections_) {
      short events = 0;
      if (!connection->peer_finished_sending_ && (connection->lingering_ || connection->isOpen())) events |= POLLIN;
      if (connection->wantsPollOut()) events |= POLLOUT;
      poll_fds.push_back({connection->fd_.get(), events, 0});
      polled.push_back(connection);
    }

    Clock::time_point wake_at = next_deadline;
    if (!accepting) wake_at = std::min(wake_at, accept_paused_until_);
    int timeout_ms = -1;
    if (wake_at != Clock::time_point::max()) {
      const auto wait = std::chrono::ceil<std::chrono::milliseconds>(wake_at - now).count();
      timeout_ms = static_cast<int>(std::clamp<long long>(wait, 0, 60'000));
    }

    const int ready = ::poll(poll_fds.data(), poll_fds.size(), timeout_ms);
    if (ready < 0) {
      if (errno == EINTR) continue;
      logger().error("IPC server for '{}': poll failed ({}); closing all connections",
                     socket_path_.native(), errnoText());
      break;
    }
    if (poll_fds[0].revents & POLLIN) {
      std::uint64_t count = 0;
      [[maybe_unused]] const ssize_t ignored = ::read(wake_fd_.get(), &count, sizeof(count));
    }
    for (std::size_t i = 0; i < polled.size(); ++i) {
      const short revents = poll_fds[i + 2].revents;
      if (revents == 0) continue;
      IpcConnection& connection = *polled[i];
      if (revents & POLLOUT) {
        std::lock_guard<std::mutex> lock(connection.mutex_);
        if (connection.state_ != IpcConnection::State::kClosed) connection.flushLocked();
      }
      if (revents & (POLLIN | POLLHUP | POLLERR)) readFrom(connection);
      if (revents & POLLNVAL) {
        std::lock_guard<std::mutex> lock(connection.mutex_);
        connection.drop_reason_ = IpcConnection::DropReason::kSocketError;
      }
    }
    if (accepting && (poll_fds[1].revents & POLLIN)) acceptConnections();
  }
}

void IpcServer::acceptConnections() {
  // Bounded so a burst of new clients cannot starve the existing ones.
  for (int accepted = 0; accepted < 64; ++accepted) {
    IpcFd fd(::accept4(listen_fd_.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!fd.valid()) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
        logger().warn("IPC server for '{}': cannot accept a client ({}); pausing",
                      socket_path_.native(), errnoText());
        accept_paused_until_ = Clock::now() + kAcceptPauseOnExhaustion;
      }
      return;  // EAGAIN: nobody else is waiting
    }
    if (connections_.size() >= kMaxConnections) {
      const std::string refusal = encodeIpcLine(makeIpcErrorReply(
          nullptr, "this servoloop node already serves " + std::to_string(kMaxConnections) +
                       " clients; close some and retry"));
      [[maybe_unused]] const ssize_t ignored =
          ::send(fd.get(), refusal.data(), refusal.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
      continue;  // fd closes here
    }
    connections_.push_back(std::shared_ptr<IpcConnection>(
        new IpcConnection(std::move(fd), next_connection_id_++, wake_fd_.get())));
    connections_accepted_.fetch_add(1);
    connection_count_.store(connections_.size());
  }
}

void IpcServer::readFrom(IpcConnection& connection) {
  if (connection.peer_finished_sending_) return;
  char buffer[kReadChunkBytes];
  const ssize_t received = ::recv(connection.fd_.get(), buffer, sizeof(buffer), 0);
  if (connection.lingering_) {
    // Dropped unread; the end of the input (or an error) lets it close.
    if (received == 0 || (received < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      connection.peer_finished_sending_ = true;
    }
    return;
  }
  if (received > 0) {
    connection.input_.append(buffer, static_cast<std::size_t>(received));
    handleInput(connection);
    return;
  }
  if (received < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
  if (received < 0) {
    std::lock_guard<std::mutex> lock(connection.mutex_);
    connection.drop_reason_ = IpcConnection::DropReason::kSocketError;
    return;
  }
  // End of file. A partial line is a request cut short: it is dropped without a
  // reply. Replies already queued are still written (the client may only have
  // shut down its sending side), then the connection closes.
  connection.peer_finished_sending_ = true;
  connection.input_.clear();
  connection.input_scanned_ = 0;
  connection.closeAfterFlush();
}

void IpcServer::handleInput(IpcConnection& connection) {
  std::string& input = connection.input_;
  std::size_t line_start = 0;
  std::size_t scan_from = connection.input_scanned_;
  while (connection.isOpen()) {
    const std::size_t newline = input.find('\n', scan_from);
    if (newline == std::string::npos) break;
    std::string_view line(input.data() + line_start, newline - line_start);
    if (line.size() > kIpcMaxRequestLineBytes) {
      rejectOversized(connection);
      return;
    }
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    handleLine(connection, line);
    line_start = newline + 1;
    scan_from = line_start;
  }
  if (!connection.isOpen()) {
    input.clear();
    connection.input_scanned_ = 0;
    return;
  }
  input.erase(0, line_start);
  connection.input_scanned_ = input.size();
  if (input.size() > kIpcMaxRequestLineBytes) rejectOversized(connection);
}

void IpcServer::rejectOversized(IpcConnection& connection) {
  requests_rejected_.fetch_add(1);
  clients_dropped_oversized_.fetch_add(1);
  logger().warn("IPC client {} sent a request line over {} bytes; closing it", connection.id(),
                kIpcMaxRequestLineBytes);
  connection.send(makeIpcErrorReply(
      nullptr, "request line longer than " + std::to_string(kIpcMaxRequestLineBytes) +
                   " bytes (1 MiB) or missing its newline; closing the connection"));
  connection.input_.clear();
  connection.input_scanned_ = 0;
  connection.closeAfterFlush();
}

void IpcServer::handleLine(IpcConnection& connection, std::string_view line) {
  if (line.find_first_not_of(" \t\r") == std::string_view::npos) return;  // blank keep-alive lines

  IpcRequestCheck checked = parseIpcRequest(line);
  if (!checked.ok) {
    requests_rejected_.fetch_add(1);
    connection.send(checked.error);
    return;
  }
  const nlohmann::json& request = checked.request;
  requests_handled_.fetch_add(1);
  nlohmann::json reply = replyFor(request, connection);
  if (reply.is_discarded()) {  // the handler replies later itself
    std::lock_guard<std::mutex> lock(connection.mutex_);
    ++connection.deferred_replies_;
    return;
  }
  connection.send(reply);
}

nlohmann::json IpcServer::replyFor(const nlohmann::json& request, IpcConnection& connection) {
  const nlohmann::json& id = request.contains(kIpcIdKey) ? request[kIpcIdKey] : nlohmann::json();
  const std::string& op = request[kIpcOpKey].get_ref<const std::string&>();
  nlohmann::json result;
  try {
    result = handler_(request, connection);
  } catch (const nlohmann::json::exception& error) {
    // Handlers read fields with the checked helpers of ipc_protocol.hpp; one
    // that slipped through still answers in their style, not nlohmann's.
    return makeIpcErrorReply(id, describeJsonException(request, error));
  } catch (const std::exception& error) {
    return makeIpcErrorReply(id, error.what());
  } catch (...) {
    return makeIpcErrorReply(id, "request '" + op + "' failed with a non-standard exception");
  }
  if (result.is_discarded()) return result;
  if (result.is_null()) return makeIpcOkReply(id);
  if (!result.is_object()) return makeIpcOkReply(id, nlohmann::json{{"result", std::move(result)}});
  if (!result.contains(kIpcOkKey)) return makeIpcOkReply(id, result);
  result[kIpcIdKey] = id;
  if (result[kIpcOkKey] != true) {
    result[kIpcOkKey] = false;
    if (!result.contains(kIpcErrorKey) || !result[kIpcErrorKey].is_string()) {
      result[kIpcErrorKey] = "request '" + op + "' failed";
    }
  }
  return result;
}

Clock::time_point IpcServer::reapConnections() {
  const Clock::time_point now = Clock::now();
  Clock::time_point next_deadline = Clock::time_point::max();
  std::vector<std::shared_ptr<IpcConnection>> finished;
  for (const auto& connection : connections_) {
    bool close_it = false;
    {
      std::lock_guard<std::mutex> lock(connection->mutex_);
      switch (connection->drop_reason_) {
        case IpcConnection::DropReason::kOutputOverflow:
          clients_dropped_slow_.fetch_add(1);
          logger().warn("IPC client {} is not reading its replies ({} bytes queued); dropping it",
                        connection->id(), kIpcMaxPendingOutputBytes);
          close_it = true;
          break;
        case IpcConnection::DropReason::kSocketError:
          close_it = true;
          break;
        case IpcConnection::DropReason::kNone:
          if (connection->state_ == IpcConnection::State::kClosing) {
            if (connection->close_deadline_ == Clock::time_point{}) {
              connection->close_deadline_ =
                  now + (connection->deferred_replies_ > 0 ? kDeferredReplyGracePeriod : kCloseGracePeriod);
            }
            if (connection->lingering_) {
              close_it = connection->peer_finished_sending_ || now >= connection->close_deadline_;
            } else if (connection->drainedLocked() && !connection->peer_finished_sending_) {
              // Every reply is written but the client may still be sending:
              // closing now could reset the connection and lose the last
              // reply. Shut our side, drop its input until it closes.
              ::shutdown(connection->fd_.get(), SHUT_WR);
              connection->lingering_ = true;
              connection->close_deadline_ = now + kLingerPeriod;
            } else {
              close_it = connection->drainedLocked() || now >= connection->close_deadline_;
            }
            if (!close_it) next_deadline = std::min(next_deadline, connection->close_deadline_);
          }
          break;
      }
    }
    if (close_it) finished.push_back(connection);
  }
  if (finished.empty()) return next_deadline;

  for (const auto& connection : finished) closeConnection(*connection);
  std::erase_if(connections_, [&](const std::shared_ptr<IpcConnection>& connection) {
    return std::find(finished.begin(), finished.end(), connection) != finished.end();
  });
  connection_count_.store(connections_.size());
  return next_deadline;
}

}  // namespace servoloop::ipc
