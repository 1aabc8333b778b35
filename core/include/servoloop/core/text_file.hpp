#pragma once
// Reading a text file a user names (URDF, xacro, YAML, launch files) whole,
// with bounds: a device such as /dev/zero, a FIFO or a folder is refused
// before anything is read, and so is a file over the size limit, each with
// one error naming the path, what it should have been and the limit.
// Non-real-time.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace servoloop {

// No description, parameter or launch file a robot needs comes near this.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{64} << 20;  // 64 MiB

// The content of the regular file at `path`. `what` names the file's role in
// errors ("URDF file", "parameter file"). Throws ConfigError when the path is
// missing ("<path>: <what> not found"), a folder, not a regular file, larger
// than `max_bytes`, or unreadable.
std::string readTextFile(const std::filesystem::path& path, const std::string& what,
                         std::uintmax_t max_bytes = kMaxTextFileBytes);

// The offset of the first byte of `text` that is not part of valid UTF-8, or
// nullopt when all of it is (XML, YAML and JSON text must be UTF-8).
std::optional<std::size_t> invalidUtf8Offset(std::string_view text);

}  // namespace servoloop
