#pragma once
// The binary contract between a servoloop plugin library and the loader.
//
// A plugin library exports exactly one C symbol, servoloop_plugin_manifest
// (kPluginEntryPointName), returning a ServoloopPluginManifest. The loader reads
// the handshake fields (api_version, then the sizes/alignments) before it
// touches anything else in the manifest: a library built against another
// servoloop API, another standard library ABI or another compiler data model is
// refused with a message instead of crashing later.
//
// Plugin authors do not write any of this by hand: they put
// SERVOLOOP_REGISTER_PLUGIN (plugin_register.hpp) at the bottom of a .cpp.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "servoloop/core/time.hpp"

namespace servoloop::plugin {

// Bumped whenever the manifest layout, the registration macro or a plugin base
// class changes in a way that breaks already-built plugins (scripts/check_abi.sh
// compares the plugin-facing libraries against a recorded baseline and fails
// when their ABI changed without a bump).
inline constexpr std::uint32_t kPluginApiVersion = 17;

// Name of the one symbol a plugin library exports.
inline constexpr const char* kPluginEntryPointName = "servoloop_plugin_manifest";

// Types whose layout plugins and the host must agree on. Their combined size
// and alignment differ between libstdc++'s old and new string ABI, debug-mode
// containers and 32/64-bit builds, which is exactly what makes a library
// unsafe to call into.
struct PluginAbiProbe {
  std::string text;
  std::vector<double> values;
  std::map<std::string, int> table;
  std::shared_ptr<int> shared;
  std::function<void()> callback;
  Time time;
  long double wide;
  void* pointer;
};

}  // namespace servoloop::plugin

extern "C" {

// One class a library provides. Plain C layout: only read after the handshake.
struct ServoloopPluginEntry {
  // The base class's kPluginKind, e.g. "controller" or "robot_hw".
  const char* kind;
  // The name users write in configuration, e.g. "effort_controllers/JointPositionController".
  const char* type_name;
  // Compiler-mangled name of the base class (typeid(Base).name()); create<Base>
  // refuses an entry whose base differs even if the kind string matches.
  const char* base_type_id;
  // Allocates one object inside the library and returns a pointer to its Base
  // subobject. May throw what the constructor throws.
  void* (*create)();
  // Deletes an object create() returned, given that same Base pointer, with the
  // library's own delete (its allocator, its destructor).
  void (*destroy)(void* base);
};

// What servoloop_plugin_manifest() returns. The first three fields are the
// handshake and never move; everything after them is trusted only once they match.
struct ServoloopPluginManifest {
  std::uint32_t api_version;
  std::uint32_t abi_probe_size;
  std::uint32_t abi_probe_align;
  std::uint32_t manifest_size;  // sizeof(ServoloopPluginManifest)
  std::uint32_t entry_size;     // sizeof(ServoloopPluginEntry)
  std::uint32_t entry_count;
  const ServoloopPluginEntry* entries;
};

// Signature of the exported entry point.
using ServoloopPluginManifestFn = const ServoloopPluginManifest* (*)();

}  // extern "C"

namespace servoloop::plugin {

// The handshake values of this build; what a loaded library must report.
inline constexpr std::uint32_t kPluginAbiProbeSize = sizeof(PluginAbiProbe);
inline constexpr std::uint32_t kPluginAbiProbeAlign = alignof(PluginAbiProbe);

}  // namespace servoloop::plugin
