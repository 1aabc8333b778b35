#include "servoloop/core/text_file.hpp"

#include <cstdint>
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

std::optional<std::size_t> invalidUtf8Offset(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = static_cast<unsigned char>(text[i]);
    std::size_t length = 0;
    std::uint32_t code = 0;
    if (byte < 0x80) {
      ++i;
      continue;
    } else if ((byte & 0xE0) == 0xC0) {
      length = 2;
      code = byte & 0x1F;
    } else if ((byte & 0xF0) == 0xE0) {
      length = 3;
      code = byte & 0x0F;
    } else if ((byte & 0xF8) == 0xF0) {
      length = 4;
      code = byte & 0x07;
    } else {
      return i;
    }
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      if ((next & 0xC0) != 0x80) return i;
      code = (code << 6) | (next & 0x3F);
    }
    // Overlong forms, UTF-16 surrogates and values past Unicode are not UTF-8.
    static constexpr std::uint32_t kLeast[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < kLeast[length] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return i;
    i += length;
  }
  return std::nullopt;
}

}  // namespace servoloop
