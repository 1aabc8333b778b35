#include "servoloop/ipc/ipc_connection.hpp"

#include <cerrno>
#include <cstdint>
#include <utility>

#include <sys/socket.h>
#include <unistd.h>

#include "servoloop/ipc/ipc_protocol.hpp"

namespace servoloop::ipc {

IpcConnection::IpcConnection(IpcFd fd, std::uint64_t id, int wake_fd)
    : fd_(std::move(fd)), id_(id), wake_fd_(wake_fd) {}

IpcConnection::~IpcConnection() = default;

bool IpcConnection::send(const nlohmann::json& message) {
  const std::string line = encodeIpcLine(message);
  std::lock_guard<std::mutex> lock(mutex_);
  if (state_ == State::kClosed || drop_reason_ != DropReason::kNone) return false;

  const std::size_t pending = pendingOutputLocked();
  if (pending + line.size() > kIpcMaxPendingOutputBytes) {
    // The client is not reading. Dropping it is the only way to bound memory
    // without ever blocking the service thread or a delivery thread.
    drop_reason_ = DropReason::kOutputOverflow;
    output_.clear();
    output_offset_ = 0;
    wakeServiceThreadLocked();
    return false;
  }
  if (output_offset_ > 0 && output_offset_ >= output_.size() / 2) {
    output_.erase(0, output_offset_);
    output_offset_ = 0;
  }
  output_ += line;
  if (!flushLocked()) {
    wakeServiceThreadLocked();
    return false;
  }
  // Something is left for the service thread to write when the socket drains;
  // it must add this socket to its POLLOUT set, so wake it on the first byte.
  if (pending == 0 && pendingOutputLocked() > 0) wakeServiceThreadLocked();
  return true;
}

bool IpcConnection::sendDeferredReply(const nlohmann::json& reply) {
  const bool sent = send(reply);
  std::lock_guard<std::mutex> lock(mutex_);
  --deferred_replies_;
  // A closing connection may have waited for this reply alone.
  if (state_ == State::kClosing) wakeServiceThreadLocked();
  return sent;
}

bool IpcConnection::flushLocked() {
  while (pendingOutputLocked() > 0) {
    // MSG_NOSIGNAL: a client that vanished must give EPIPE, never SIGPIPE.
    const ssize_t written = ::send(fd_.get(), output_.data() + output_offset_, pendingOutputLocked(),
                                   MSG_NOSIGNAL | MSG_DONTWAIT);
    if (written > 0) {
      output_offset_ += static_cast<std::size_t>(written);
      continue;
    }
    if (written < 0 && errno == EINTR) continue;
    if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    drop_reason_ = DropReason::kSocketError;
    output_.clear();
    output_offset_ = 0;
    return false;
  }
  output_.clear();
  output_offset_ = 0;
  return true;
}

void IpcConnection::wakeServiceThreadLocked() {
  if (state_ == State::kClosed || wake_fd_ < 0) return;
  const std::uint64_t one = 1;
  // An eventfd write only fails when the counter would overflow, and then the
  // service thread has a wake-up pending anyway.
  [[maybe_unused]] const ssize_t ignored = ::write(wake_fd_, &one, sizeof(one));
}

void IpcConnection::onClose(CloseCallback callback) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (state_ != State::kClosed) {
      close_callbacks_.push_back(std::move(callback));
      return;
    }
  }
  callback();
}

void IpcConnection::closeAfterFlush() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (state_ != State::kOpen) return;
  state_ = State::kClosing;
  wakeServiceThreadLocked();
}

bool IpcConnection::isOpen() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_ == State::kOpen && drop_reason_ == DropReason::kNone;
}

bool IpcConnection::wantsPollOut() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_ != State::kClosed && pendingOutputLocked() > 0;
}

std::vector<IpcConnection::CloseCallback> IpcConnection::closeNow() {
  std::lock_guard<std::mutex> lock(mutex_);
  state_ = State::kClosed;
  fd_.reset();
  output_.clear();
  output_offset_ = 0;
  input_.clear();
  return std::exchange(close_callbacks_, {});
}

}  // namespace servoloop::ipc
