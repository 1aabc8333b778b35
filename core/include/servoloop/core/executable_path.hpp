#pragma once
// Where the running program is: servoloop finds its plugins and helper
// programs next to it (bin/, lib/servoloop/plugins, share/servoloop), in the
// build tree and after `cmake --install` alike.
#include <filesystem>
#include <system_error>

namespace servoloop {

// The directory of the running executable (/proc/self/exe); empty, with
// `error` set, when it cannot be read.
std::filesystem::path executableDirectory(std::error_code& error);

// The directory of the loaded file (shared library or executable) that holds
// `address`, symbolic links resolved: a library finds what is installed
// beside it. Empty, with `error` set, when it cannot be found.
std::filesystem::path loadedObjectDirectory(const void* address, std::error_code& error);

}  // namespace servoloop
