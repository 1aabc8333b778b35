#pragma once
// Helpers for the IPC tests: a private temporary run directory selected
// through SERVOLOOP_RUN_DIR, and a raw socket client that can misbehave in
// ways IpcClient never would (garbage, cut-off lines, not reading).
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "servoloop/ipc/ipc_unix_socket.hpp"

namespace servoloop::ipc::testing {

// Sets SERVOLOOP_RUN_DIR to "<fresh /tmp dir>/run" (not created yet) for the
// test's lifetime and restores the previous value afterwards. The path stays
// short so sockets fit in sun_path.
class ScopedRunDir {
 public:
  ScopedRunDir() {
    char pattern[] = "/tmp/slipc-XXXXXX";
    const char* made = ::mkdtemp(pattern);
    if (made == nullptr) throw std::runtime_error("mkdtemp failed");
    base_ = made;
    run_dir_ = base_ / "run";
    if (const char* previous = std::getenv("SERVOLOOP_RUN_DIR")) previous_ = previous;
    ::setenv("SERVOLOOP_RUN_DIR", run_dir_.c_str(), 1);
  }
  ~ScopedRunDir() {
    if (previous_) {
      ::setenv("SERVOLOOP_RUN_DIR", previous_->c_str(), 1);
    } else {
      ::unsetenv("SERVOLOOP_RUN_DIR");
    }
    std::error_code ignored;
    std::filesystem::permissions(run_dir_, std::filesystem::perms::owner_all, ignored);
    std::filesystem::remove_all(base_, ignored);
  }
  ScopedRunDir(const ScopedRunDir&) = delete;
  ScopedRunDir& operator=(const ScopedRunDir&) = delete;

  const std::filesystem::path& base() const { return base_; }
  const std::filesystem::path& runDir() const { return run_dir_; }

 private:
  std::filesystem::path base_;
  std::filesystem::path run_dir_;
  std::optional<std::string> previous_;
};

// A bare Unix socket connection for sending arbitrary bytes.
class RawClient {
 public:
  explicit RawClient(const std::filesystem::path& socket_path) {
    if (tryConnectUnixSocket(socket_path, fd_) != IpcConnectResult::kConnected) {
      throw std::runtime_error("RawClient: cannot connect to " + socket_path.native());
    }
  }

  // Writes all of `data` (waiting up to `timeout_s` for room); false if the
  // server closed the connection or the time ran out first.
  bool sendBytes(std::string_view data, double timeout_s = 5.0) {
    const auto deadline = deadlineAfter(timeout_s);
    std::size_t sent = 0;
    while (sent < data.size()) {
      const ssize_t n = ::send(fd_.get(), data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
      if (n > 0) {
        sent += static_cast<std::size_t>(n);
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
        if (std::chrono::steady_clock::now() >= deadline) return false;
        pollfd writable{fd_.get(), POLLOUT, 0};
        ::poll(&writable, 1, 20);
        continue;
      }
      return false;
    }
    return true;
  }

  // The next line without its '\n'; nullopt on timeout or end of stream.
  std::optional<std::string> readLine(double timeout_s = 5.0) {
    const auto deadline = deadlineAfter(timeout_s);
    while (true) {
      const auto newline = buffer_.find('\n');
      if (newline != std::string::npos) {
        std::string line = buffer_.substr(0, newline);
        buffer_.erase(0, newline + 1);
        return line;
      }
      if (!readSome(deadline)) return std::nullopt;
    }
  }

  // True once the server has closed the connection (end of stream or reset)
  // within `timeout_s`; data still arriving is read and kept meanwhile.
  bool waitForClose(double timeout_s = 5.0) {
    const auto deadline = deadlineAfter(timeout_s);
    while (std::chrono::steady_clock::now() < deadline) {
      if (!readSome(deadline)) return closed_;
    }
    return closed_;
  }

  void close() { fd_.reset(); }
  int fd() const { return fd_.get(); }

 private:
  static std::chrono::steady_clock::time_point deadlineAfter(double timeout_s) {
    return std::chrono::steady_clock::now() +
           std::chrono::duration_cast<std::chrono::steady_clock::duration>(
               std::chrono::duration<double>(timeout_s));
  }

  // Reads what is there; false on end of stream, reset or timeout.
  bool readSome(std::chrono::steady_clock::time_point deadline) {
    while (true) {
      const auto remaining = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      if (remaining.count() <= 0) return false;
      pollfd readable{fd_.get(), POLLIN, 0};
      if (::poll(&readable, 1, static_cast<int>(remaining.count())) <= 0) continue;
      char chunk[65536];
      const ssize_t n = ::recv(fd_.get(), chunk, sizeof(chunk), MSG_DONTWAIT);
      if (n > 0) {
        buffer_.append(chunk, static_cast<std::size_t>(n));
        return true;
      }
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
      closed_ = true;
      return false;
    }
  }

  IpcFd fd_;
  std::string buffer_;
  bool closed_ = false;
};

// One line on a fresh connection and the line that answers it; nullopt when
// connecting, sending or the reply fails within timeout_s each.
inline std::optional<std::string> requestLine(const std::filesystem::path& socket_path, std::string_view line,
                                              double timeout_s = 10.0) {
  try {
    RawClient client(socket_path);
    if (!client.sendBytes(std::string(line) + "\n", timeout_s)) return std::nullopt;
    return client.readLine(timeout_s);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // no node listening
  }
}

// Polls `condition` every 5 ms for up to `timeout_s`; returns its last value.
template <typename Condition>
bool eventually(Condition condition, double timeout_s = 5.0) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return condition();
}

}  // namespace servoloop::ipc::testing
