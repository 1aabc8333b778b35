// The running program's directory, and a loaded library's.
#include "servoloop/core/executable_path.hpp"

#include <dlfcn.h>

namespace servoloop {

std::filesystem::path executableDirectory(std::error_code& error) {
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path() : exe.parent_path();
}

std::filesystem::path loadedObjectDirectory(const void* address, std::error_code& error) {
  Dl_info info{};
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) {
    error = std::make_error_code(std::errc::no_such_file_or_directory);
    return {};
  }
  const std::filesystem::path file = std::filesystem::weakly_canonical(info.dli_fname, error);
  return error ? std::filesystem::path() : file.parent_path();
}

}  // namespace servoloop
