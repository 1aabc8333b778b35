#pragma once
// Where a node's IPC socket lives, and the checks that keep that place private.
//
// Every node listens on one Unix socket in a per-user run directory:
//   $SERVOLOOP_RUN_DIR            if set (tests use a temporary one), else
//   $XDG_RUNTIME_DIR/servoloop    if XDG_RUNTIME_DIR is set, else
//   /tmp/servoloop-<uid>.
// The directory is created with mode 0700; one that exists but is not a real
// directory, is owned by another user, or is open to group/others is refused,
// because anybody who can write there could stand in for a node.
//
// The socket of the node serving robot namespace "/one_DOF_robot" is
// "<run dir>/one_DOF_robot.sock". None of these functions runs on the
// real-time thread.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace servoloop::ipc {

// The run directory as the environment selects it; touches nothing on disk.
std::filesystem::path ipcRunDirectory();

// Creates `directory` (mode 0700, missing parents with default permissions)
// or checks that the existing one is a directory owned by the current user
// with no group/other permissions. Throws servoloop::Error naming the
// directory and the fix otherwise.
void ensurePrivateDirectory(const std::filesystem::path& directory);

// Like ensurePrivateDirectory, but a missing directory is fine (returns false,
// creates nothing); an existing one must pass the same checks (returns true).
bool checkPrivateDirectoryIfPresent(const std::filesystem::path& directory);

// File stem for a node name: leading/trailing '/' removed, inner '/' become
// '.', any character other than [A-Za-z0-9_-] becomes '_'; "" and "/" give
// "default". "/one_DOF_robot" -> "one_DOF_robot", "/arm/left" -> "arm.left".
std::string socketStemFor(std::string_view node_name);

// Inverse of socketStemFor for names made of ROS name characters:
// "one_DOF_robot" -> "/one_DOF_robot", "arm.left" -> "/arm/left", "default" -> "/".
std::string nodeNameForStem(std::string_view stem);

// The node name a socket path stands for (nodeNameForStem of its stem).
std::string nodeNameForSocketPath(const std::filesystem::path& socket_path);

// "<ipcRunDirectory()>/<socketStemFor(node_name)>.sock"; touches nothing on disk.
std::filesystem::path socketPathFor(std::string_view node_name);

// A node socket found in the run directory.
struct IpcNodeEntry {
  std::string node_name;               // e.g. "/one_DOF_robot"
  std::filesystem::path socket_path;   // e.g. "/run/user/1000/servoloop/one_DOF_robot.sock"
  bool accepting = false;              // a server accepted a connection just now (false: stale file)
};

// The node sockets present in the run directory, sorted by node name; empty if
// the directory does not exist. Each is probed with one connection attempt.
// Throws servoloop::Error if the directory exists but is not private.
std::vector<IpcNodeEntry> listNodes();

}  // namespace servoloop::ipc
