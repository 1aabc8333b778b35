#pragma once
// What a plugin library provides, read from the library file without running
// any of its code.
//
// SERVOLOOP_REGISTER_PLUGIN (plugin_register.hpp) places one record per
// registered class in the library's ELF section kPluginIndexSection:
//
//   "servoloop-plugin\0" <API version, decimal> "\0" <kind> "\0" <type name> "\0"
//
// Listing the types on the plugin path reads these records from the files
// (plugin/src/plugin_index_reader.hpp); a library is dlopen'ed (its static
// constructors run) only when one of its types is first created. Files without
// the section are not servoloop plugins and are passed over quietly.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "servoloop/plugin/plugin_api.hpp"

namespace servoloop::plugin {

inline constexpr const char* kPluginIndexSection = "servoloop_plugin_index";
inline constexpr std::string_view kPluginIndexMagic = "servoloop-plugin";

namespace detail {

constexpr std::size_t decimalDigits(std::uint32_t value) {
  std::size_t digits = 1;
  while (value >= 10) {
    value /= 10;
    ++digits;
  }
  return digits;
}

// The record of one registered class, built at compile time.
template <class Base, std::size_t TypeNameSize>
constexpr auto pluginIndexRecord(const char (&type_name)[TypeNameSize]) {
  constexpr std::string_view kind = Base::kPluginKind;
  constexpr std::size_t version_digits = decimalDigits(kPluginApiVersion);
  // TypeNameSize counts the literal's terminating NUL.
  std::array<char, kPluginIndexMagic.size() + 1 + version_digits + 1 + kind.size() + 1 + TypeNameSize>
      record{};
  std::size_t at = 0;
  for (char c : kPluginIndexMagic) record[at++] = c;
  record[at++] = '\0';
  std::uint32_t version = kPluginApiVersion;
  for (std::size_t i = 0; i < version_digits; ++i) {
    record[at + version_digits - 1 - i] = static_cast<char>('0' + version % 10);
    version /= 10;
  }
  at += version_digits;
  record[at++] = '\0';
  for (char c : kind) record[at++] = c;
  record[at++] = '\0';
  for (std::size_t i = 0; i < TypeNameSize; ++i) record[at++] = type_name[i];
  return record;
}

}  // namespace detail
}  // namespace servoloop::plugin
