#pragma once
// Small POSIX helpers shared by the IPC server, client and tests: an owning
// file descriptor and Unix stream socket connection. Non-real-time only.
#include <filesystem>
#include <string_view>

#include <sys/un.h>

namespace servoloop::ipc {

// Owns one file descriptor; closes it on destruction. Move-only.
class IpcFd {
 public:
  IpcFd() = default;
  explicit IpcFd(int fd) : fd_(fd) {}
  ~IpcFd() { reset(); }
  IpcFd(IpcFd&& other) noexcept : fd_(other.release()) {}
  IpcFd& operator=(IpcFd&& other) noexcept;
  IpcFd(const IpcFd&) = delete;
  IpcFd& operator=(const IpcFd&) = delete;

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  int release();
  void reset(int fd = -1);

 private:
  int fd_ = -1;
};

// sockaddr_un for `path`; throws servoloop::Error if the path does not fit in
// sun_path (about 107 bytes), telling the user to pick a shorter run directory.
sockaddr_un makeUnixAddress(const std::filesystem::path& path);

// Outcome of one connection attempt.
enum class IpcConnectResult {
  kConnected,
  kNoListener,       // no socket file, or a stale one nobody listens on
  kBusy,             // the listener's backlog is full; try again
  kPermissionDenied, // the socket or its directory belongs to someone else
};

// One non-blocking connection attempt to the Unix stream socket at `path`. On
// kConnected, `out` holds the connected socket, non-blocking and close-on-exec.
// Other system errors throw servoloop::Error naming the path.
IpcConnectResult tryConnectUnixSocket(const std::filesystem::path& path, IpcFd& out);

// Sets O_NONBLOCK on `fd`; throws servoloop::Error on failure.
void setNonBlocking(int fd);

}  // namespace servoloop::ipc
