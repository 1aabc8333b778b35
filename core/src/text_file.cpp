#include "servoloop/core/text_file.hpp"

#include <fstream>

#include "servoloop/core/errors.hpp"

namespace servoloop {

std::string readTextFile(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw ConfigError(path.string() + ": " + what + " not found; check the path");
  if (fs::is_directory(status)) throw ConfigError(path.string() + ": is a folder, not a " + what);
  if (!fs::is_regular_file(status)) {
    throw ConfigError(path.string() + ": is not a regular file (a device, FIFO or socket), so it is not read; give "
                      "the path of a " + what);
  }
  const auto size = fs::file_size(path, ec);
  const auto limit_text = [&] { return std::to_string(max_bytes >> 20) + " MiB"; };
  if (!ec && size > max_bytes) {
    throw ConfigError(path.string() + ": " + what + " of " + std::to_string(size >> 20) + " MiB; the limit is " +
                      limit_text());
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path.string() + ": " + what + " cannot be read; check its permissions");
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    // The file may grow while it is read.
    if (text.size() > max_bytes) throw ConfigError(path.string() + ": " + what + " over the limit of " + limit_text());
  }
  return text;
}

}  // namespace servoloop
