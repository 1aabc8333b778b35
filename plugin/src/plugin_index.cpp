#include "plugin_index_reader.hpp"

#include <elf.h>

#include <charconv>
#include <cstring>
#include <fstream>
#include <limits>

namespace servoloop::plugin {

namespace fs = std::filesystem;

namespace {

// Index sections are a few hundred bytes; anything far larger is not one.
constexpr std::uint64_t kMaxIndexBytes = 1u << 20;
constexpr std::uint16_t kMaxSections = 1u << 14;
constexpr std::uint64_t kMaxSectionNamesBytes = 1u << 20;

// Reads `size` bytes at `offset` of `in` into `out`; false when the file is shorter.
bool readAt(std::ifstream& in, std::uint64_t file_size, std::uint64_t offset, std::uint64_t size,
            void* out) {
  if (offset > file_size || size > file_size - offset) return false;
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(static_cast<char*>(out), static_cast<std::streamsize>(size));
  return static_cast<std::uint64_t>(in.gcount()) == size;
}

std::optional<std::string> indexSectionBytes(const fs::path& library) {
  std::error_code error;
  const std::uint64_t file_size = fs::file_size(library, error);
  if (error) return std::nullopt;
  std::ifstream in(library, std::ios::binary);
  if (!in) return std::nullopt;

  Elf64_Ehdr header{};
  if (!readAt(in, file_size, 0, sizeof(header), &header)) return std::nullopt;
  // Only shared objects this process could load: 64-bit, this byte order, this machine.
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
      header.e_ident[EI_DATA] != ELFDATA2LSB || header.e_type != ET_DYN ||
#if defined(__x86_64__)
      header.e_machine != EM_X86_64 ||
#elif defined(__aarch64__)
      header.e_machine != EM_AARCH64 ||
#endif
      header.e_shentsize != sizeof(Elf64_Shdr) || header.e_shnum == 0 || header.e_shnum > kMaxSections ||
      header.e_shstrndx >= header.e_shnum) {
    return std::nullopt;
  }
  std::vector<Elf64_Shdr> sections(header.e_shnum);
  if (!readAt(in, file_size, header.e_shoff, sizeof(Elf64_Shdr) * sections.size(), sections.data())) {
    return std::nullopt;
  }
  const Elf64_Shdr& names_header = sections[header.e_shstrndx];
  if (names_header.sh_size == 0 || names_header.sh_size > kMaxSectionNamesBytes) return std::nullopt;
  std::string names(names_header.sh_size, '\0');
  if (!readAt(in, file_size, names_header.sh_offset, names.size(), names.data())) return std::nullopt;

  const std::string_view wanted = kPluginIndexSection;
  for (const Elf64_Shdr& section : sections) {
    if (section.sh_name >= names.size()) continue;
    const std::string_view name(names.c_str() + section.sh_name);
    if (name != wanted) continue;
    if (section.sh_type != SHT_PROGBITS || section.sh_size == 0 || section.sh_size > kMaxIndexBytes) {
      return std::nullopt;
    }
    std::string bytes(section.sh_size, '\0');
    if (!readAt(in, file_size, section.sh_offset, bytes.size(), bytes.data())) return std::nullopt;
    return bytes;
  }
  return std::nullopt;
}

}  // namespace

std::vector<PluginIndexEntry> parsePluginIndex(std::string_view section) {
  std::vector<PluginIndexEntry> entries;
  // The next NUL-terminated string at `at`, or nullopt at the end of the section.
  const auto next_string = [&](std::size_t& at) -> std::optional<std::string_view> {
    const std::size_t end = section.find('\0', at);
    if (end == std::string_view::npos) return std::nullopt;
    const std::string_view text = section.substr(at, end - at);
    at = end + 1;
    return text;
  };
  std::size_t at = 0;
  while (true) {
    // Records may be padded apart with NULs (alignment, sanitizer redzones).
    const std::size_t start = section.find(kPluginIndexMagic, at);
    if (start == std::string_view::npos) break;
    at = start;
    const auto magic = next_string(at);
    const auto version = next_string(at);
    const auto kind = next_string(at);
    const auto type_name = next_string(at);
    if (!magic || !version || !kind || !type_name) break;
    if (*magic != kPluginIndexMagic || kind->empty() || type_name->empty()) continue;
    PluginIndexEntry entry;
    const auto [end, ec] = std::from_chars(version->data(), version->data() + version->size(), entry.api_version);
    if (ec != std::errc() || end != version->data() + version->size()) continue;
    entry.kind = std::string(*kind);
    entry.type_name = std::string(*type_name);
    entries.push_back(std::move(entry));
  }
  return entries;
}

std::optional<std::vector<PluginIndexEntry>> readPluginIndex(const fs::path& library) {
  const auto bytes = indexSectionBytes(library);
  if (!bytes) return std::nullopt;
  return parsePluginIndex(*bytes);
}

}  // namespace servoloop::plugin
