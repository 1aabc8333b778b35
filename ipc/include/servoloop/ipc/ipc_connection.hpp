#pragma once
// One client connection of an IpcServer, as request handlers see it.
//
// Handlers receive it by reference; code that pushes stream messages later
// from another thread (e.g. a topic delivery thread) keeps `shared()` and
// registers `onClose` to drop its subscription when the client goes away.
// Nothing here runs on the real-time thread.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "servoloop/ipc/ipc_unix_socket.hpp"

namespace servoloop::ipc {

class IpcServer;

class IpcConnection : public std::enable_shared_from_this<IpcConnection> {
 public:
  using CloseCallback = std::function<void()>;

  ~IpcConnection();
  IpcConnection(const IpcConnection&) = delete;
  IpcConnection& operator=(const IpcConnection&) = delete;

  // Any thread. Queues `message` as one line and writes as much as the socket
  // takes without blocking; the server's service thread writes the rest.
  // Returns false if the connection is closed, or if this message would put
  // more than kIpcMaxPendingOutputBytes in its queue: the client is then not
  // reading, and the connection is dropped.
  bool send(const nlohmann::json& message);

  // Any thread. send() for the reply to a request whose handler returned
  // IpcServer::deferredReply(). A connection whose client has stopped sending
  // (end of file, or a half-closed socket) stays until every deferred reply
  // is written, so a request that ran is never left without its reply.
  bool sendDeferredReply(const nlohmann::json& reply);

  // Any thread. Runs `callback` once when the connection closes, on the
  // server's service thread (or in IpcServer::stop()); runs it at once, in the
  // calling thread, if the connection is already closed. Callbacks must not
  // call IpcServer::stop().
  void onClose(CloseCallback callback);

  // Any thread. Stops reading requests; closes once what is queued has been
  // written (or after a short grace period if the client does not read it).
  void closeAfterFlush();

  // Any thread. False once the connection is closing or closed.
  bool isOpen() const;

  // Unique among the connections of one server run; for logs and as a
  // subscription key.
  std::uint64_t id() const { return id_; }

  std::shared_ptr<IpcConnection> shared() { return shared_from_this(); }

 private:
  friend class IpcServer;

  enum class State { kOpen, kClosing, kClosed };
  enum class DropReason { kNone, kSocketError, kOutputOverflow };

  IpcConnection(IpcFd fd, std::uint64_t id, int wake_fd);

  // All *Locked members expect mutex_ held.
  std::size_t pendingOutputLocked() const { return output_.size() - output_offset_; }
  // Nothing queued and no deferred reply still to come.
  bool drainedLocked() const { return pendingOutputLocked() == 0 && deferred_replies_ == 0; }
  // Writes queued output until the socket would block; false on a fatal
  // socket error (the connection is then marked failed).
  bool flushLocked();
  void wakeServiceThreadLocked();

  // Service thread only.
  bool wantsPollOut() const;
  // Closes the socket; returns the close callbacks for the caller to run
  // without the lock held.
  std::vector<CloseCallback> closeNow();

  mutable std::mutex mutex_;
  IpcFd fd_;
  const std::uint64_t id_;
  const int wake_fd_;  // owned by the server; valid while state_ != kClosed
  State state_ = State::kOpen;
  DropReason drop_reason_ = DropReason::kNone;
  // Deferred requests not yet answered. Signed: a worker's reply may be sent
  // before the server has counted its request.
  long deferred_replies_ = 0;
  std::string output_;            // bytes queued for the socket
  std::size_t output_offset_ = 0; // first byte of output_ not yet written
  std::vector<CloseCallback> close_callbacks_;

  // Owned by the service thread; never touched by other threads.
  std::string input_;                 // received bytes not yet handled
  std::size_t input_scanned_ = 0;     // prefix of input_ known to hold no '\n'
  bool peer_finished_sending_ = false;
  std::chrono::steady_clock::time_point close_deadline_{};
  // After the last reply of a closing connection is written: our side is shut
  // down for writing and what the client still sends is read and dropped, so
  // closing never resets the connection before the client read that reply.
  bool lingering_ = false;
};

}  // namespace servoloop::ipc
