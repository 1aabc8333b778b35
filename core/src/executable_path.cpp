// The running program's directory.
#include "servoloop/core/executable_path.hpp"

namespace servoloop {

std::filesystem::path executableDirectory(std::error_code& error) {
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path() : exe.parent_path();
}

}  // namespace servoloop
