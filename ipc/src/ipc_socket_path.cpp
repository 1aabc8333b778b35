#include "servoloop/ipc/ipc_socket_path.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include <sys/stat.h>
#include <unistd.h>

#include "servoloop/ipc/ipc_unix_socket.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::ipc {

namespace {

constexpr std::string_view kSocketSuffix = ".sock";
constexpr std::string_view kDefaultStem = "default";

std::string environmentValue(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? std::string(value) : std::string();
}

std::string octalMode(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof(text), "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// Throws unless `directory` (already lstat'ed into `info`) is a real directory
// owned by us and closed to group and others.
void requirePrivate(const std::filesystem::path& directory, const struct stat& info) {
  const std::string where = "servoloop run directory '" + directory.native() + "'";
  if (S_ISLNK(info.st_mode)) {
    throw Error(where + " is a symbolic link; refusing to use it for IPC sockets: remove it, or set "
                "SERVOLOOP_RUN_DIR to a private directory");
  }
  if (!S_ISDIR(info.st_mode)) {
    throw Error(where + " exists but is not a directory: remove it, or set SERVOLOOP_RUN_DIR to a "
                "private directory");
  }
  if (info.st_uid != ::geteuid()) {
    throw Error(where + " is owned by user id " + std::to_string(info.st_uid) + ", not by you (" +
                std::to_string(::geteuid()) + "); refusing to use it for IPC sockets: set "
                "SERVOLOOP_RUN_DIR to a directory of your own");
  }
  if ((info.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw Error(where + " has mode " + octalMode(info.st_mode) +
                ", open to group/others, so another user could stand in for a node: run `chmod 700 " +
                directory.native() + "` or set SERVOLOOP_RUN_DIR to a private directory");
  }
}

}  // namespace

std::filesystem::path ipcRunDirectory() {
  if (std::string dir = environmentValue("SERVOLOOP_RUN_DIR"); !dir.empty()) return dir;
  if (std::string runtime = environmentValue("XDG_RUNTIME_DIR"); !runtime.empty()) {
    return std::filesystem::path(runtime) / "servoloop";
  }
  return std::filesystem::path("/tmp") / ("servoloop-" + std::to_string(::geteuid()));
}

bool checkPrivateDirectoryIfPresent(const std::filesystem::path& directory) {
  struct stat info {};
  if (::lstat(directory.c_str(), &info) != 0) {
    if (errno == ENOENT) return false;
    throw Error("cannot inspect servoloop run directory '" + directory.native() +
                "': " + std::strerror(errno));
  }
  requirePrivate(directory, info);
  return true;
}

void ensurePrivateDirectory(const std::filesystem::path& directory) {
  if (checkPrivateDirectoryIfPresent(directory)) return;
  if (directory.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(directory.parent_path(), error);
    if (error) {
      throw Error("cannot create the parent of servoloop run directory '" + directory.native() +
                  "': " + error.message());
    }
  }
  const bool created_here = ::mkdir(directory.c_str(), 0700) == 0;
  if (!created_here && errno != EEXIST) {
    throw Error("cannot create servoloop run directory '" + directory.native() +
                "': " + std::strerror(errno) + ": set SERVOLOOP_RUN_DIR to a writable directory");
  }
  // The umask only removes bits, but a strange one may remove the owner's own;
  // ours must end up exactly 0700. A directory another process created first
  // (EEXIST) is only checked, never changed.
  if (created_here) ::chmod(directory.c_str(), 0700);
  struct stat info {};
  if (::lstat(directory.c_str(), &info) != 0) {
    throw Error("cannot inspect servoloop run directory '" + directory.native() +
                "': " + std::strerror(errno));
  }
  requirePrivate(directory, info);
}

std::string socketStemFor(std::string_view node_name) {
  const auto first = node_name.find_first_not_of('/');
  if (first == std::string_view::npos) return std::string(kDefaultStem);
  const auto last = node_name.find_last_not_of('/');
  std::string stem(node_name.substr(first, last - first + 1));
  for (char& c : stem) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '_' || c == '-';
    if (c == '/') {
      c = '.';
    } else if (!plain) {
      c = '_';
    }
  }
  return stem;
}

std::string nodeNameForStem(std::string_view stem) {
  if (stem.empty() || stem == kDefaultStem) return "/";
  std::string name = "/";
  name += stem;
  std::replace(name.begin(), name.end(), '.', '/');
  return name;
}

std::string nodeNameForSocketPath(const std::filesystem::path& socket_path) {
  return nodeNameForStem(socket_path.stem().native());
}

std::filesystem::path socketPathFor(std::string_view node_name) {
  return ipcRunDirectory() / (socketStemFor(node_name) + std::string(kSocketSuffix));
}

std::vector<IpcNodeEntry> listNodes() {
  const std::filesystem::path directory = ipcRunDirectory();
  std::vector<IpcNodeEntry> nodes;
  if (!checkPrivateDirectoryIfPresent(directory)) return nodes;

  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != kSocketSuffix) continue;
    std::error_code type_error;
    if (!entry.is_socket(type_error)) continue;
    IpcNodeEntry node;
    node.node_name = nodeNameForSocketPath(path);
    node.socket_path = path;
    IpcFd probe;
    try {
      node.accepting = tryConnectUnixSocket(path, probe) == IpcConnectResult::kConnected;
    } catch (const Error&) {
      node.accepting = false;  // e.g. a path too long to connect to: not a usable node
    }
    nodes.push_back(std::move(node));
  }
  if (error) {
    throw Error("cannot list servoloop run directory '" + directory.native() + "': " + error.message());
  }
  std::sort(nodes.begin(), nodes.end(),
            [](const IpcNodeEntry& a, const IpcNodeEntry& b) { return a.node_name < b.node_name; });
  return nodes;
}

}  // namespace servoloop::ipc
