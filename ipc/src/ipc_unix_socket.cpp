#include "servoloop/ipc/ipc_unix_socket.hpp"

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "servoloop/core/errors.hpp"

namespace servoloop::ipc {

IpcFd& IpcFd::operator=(IpcFd&& other) noexcept {
  if (this != &other) reset(other.release());
  return *this;
}

int IpcFd::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

void IpcFd::reset(int fd) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
}

sockaddr_un makeUnixAddress(const std::filesystem::path& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string& text = path.native();
  if (text.empty() || text.size() >= sizeof(address.sun_path)) {
    throw Error("IPC socket path '" + text + "' is " + std::to_string(text.size()) +
                " bytes; a Unix socket path must be 1 to " +
                std::to_string(sizeof(address.sun_path) - 1) +
                " bytes: set SERVOLOOP_RUN_DIR to a shorter directory");
  }
  std::memcpy(address.sun_path, text.c_str(), text.size() + 1);
  return address;
}

void setNonBlocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
    throw Error(std::string("cannot make an IPC socket non-blocking: ") + std::strerror(errno));
  }
}

IpcConnectResult tryConnectUnixSocket(const std::filesystem::path& path, IpcFd& out) {
  const sockaddr_un address = makeUnixAddress(path);
  IpcFd fd(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (!fd.valid()) {
    throw Error(std::string("cannot create a Unix socket: ") + std::strerror(errno));
  }
  // A Unix stream connect completes at once or fails at once; EAGAIN means the
  // listener's backlog is full, never "in progress".
  if (::connect(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0) {
    out = std::move(fd);
    return IpcConnectResult::kConnected;
  }
  const int error = errno;
  switch (error) {
    case ENOENT:
    case ECONNREFUSED:
    case ENOTDIR:
    case ENOTSOCK:
      return IpcConnectResult::kNoListener;
    case EAGAIN:
    case EINTR:
      return IpcConnectResult::kBusy;
    case EACCES:
    case EPERM:
      return IpcConnectResult::kPermissionDenied;
    default:
      throw Error("cannot connect to IPC socket '" + path.native() + "': " + std::strerror(error));
  }
}

}  // namespace servoloop::ipc
