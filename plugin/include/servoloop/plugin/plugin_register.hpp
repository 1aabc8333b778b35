#pragma once
// Registration of plugin classes. Include this header only from the sources of
// a plugin library (a MODULE library built with servoloop_add_plugin) and put one
// macro per class at the bottom of the class's .cpp:
//
//   SERVOLOOP_REGISTER_PLUGIN(my_pkg::MyController,
//                             servoloop::controller_manager::ControllerBase,
//                             "my_pkg/MyController")
//
// Base must declare `static constexpr const char* kPluginKind` ("controller",
// "robot_hw", ...). A library may register any number of classes from any
// number of .cpp files; including this header also defines the library's one
// exported entry point, servoloop_plugin_manifest, which lists all of them
// together with the API-version and ABI handshake. Each registration also
// writes a record into the library's plugin index (plugin_index.hpp), so that
// the loader can list the library's types without loading it.
#include <type_traits>
#include <typeinfo>
#include <vector>

#include "servoloop/plugin/plugin_api.hpp"
#include "servoloop/plugin/plugin_index.hpp"

namespace servoloop::plugin::detail {

// This library's entries. Hidden visibility keeps one registry per library:
// with default visibility the static would become a process-wide unique symbol
// shared by every plugin loaded.
struct PluginRegistry {
  std::vector<ServoloopPluginEntry> entries;
  ServoloopPluginManifest manifest{};
};

[[gnu::visibility("hidden")]] inline PluginRegistry& pluginRegistry() {
  static PluginRegistry registry;
  return registry;
}

template <class Base>
concept PluginBase = requires {
  { Base::kPluginKind } -> std::convertible_to<const char*>;
};

template <class Derived, class Base>
void* createPlugin() {
  Base* base = new Derived();
  return base;
}

template <class Derived, class Base>
void destroyPlugin(void* base) {
  // Delete through the most-derived type so that a base without a virtual
  // destructor is still destroyed correctly, with this library's operator delete.
  delete static_cast<Derived*>(static_cast<Base*>(base));
}

// One static instance per SERVOLOOP_REGISTER_PLUGIN; runs while dlopen loads
// the library, before the loader asks for the manifest.
template <class Derived, class Base>
struct PluginRegistrar {
  static_assert(std::is_base_of_v<Base, Derived>,
                "SERVOLOOP_REGISTER_PLUGIN: the class must derive from the base class given");
  static_assert(PluginBase<Base>,
                "SERVOLOOP_REGISTER_PLUGIN: the base class must declare "
                "static constexpr const char* kPluginKind");
  static_assert(std::is_default_constructible_v<Derived>,
                "SERVOLOOP_REGISTER_PLUGIN: plugin classes need a default constructor; "
                "configure them in their init/configure method instead");

  explicit PluginRegistrar(const char* type_name) {
    pluginRegistry().entries.push_back(ServoloopPluginEntry{
        Base::kPluginKind, type_name, typeid(Base).name(), &createPlugin<Derived, Base>,
        &destroyPlugin<Derived, Base>});
  }
};

}  // namespace servoloop::plugin::detail

// The library's entry point. Inline and `used`: every plugin source that
// includes this header emits the same definition and the linker keeps one.
extern "C" [[gnu::visibility("default"), gnu::used]] inline const ServoloopPluginManifest*
servoloop_plugin_manifest() {
  using namespace servoloop::plugin;
  auto& registry = detail::pluginRegistry();
  registry.manifest = ServoloopPluginManifest{
      kPluginApiVersion,
      kPluginAbiProbeSize,
      kPluginAbiProbeAlign,
      static_cast<std::uint32_t>(sizeof(ServoloopPluginManifest)),
      static_cast<std::uint32_t>(sizeof(ServoloopPluginEntry)),
      static_cast<std::uint32_t>(registry.entries.size()),
      registry.entries.data()};
  return &registry.manifest;
}

#define SERVOLOOP_PLUGIN_CONCAT_INNER(a, b) a##b
#define SERVOLOOP_PLUGIN_CONCAT(a, b) SERVOLOOP_PLUGIN_CONCAT_INNER(a, b)

// Registers Derived (a class deriving from Base) under type_name, a string
// literal such as "my_pkg/MyController". Use at namespace scope in a .cpp.
#define SERVOLOOP_REGISTER_PLUGIN(Derived, Base, type_name)                                        \
  namespace {                                                                                      \
  const ::servoloop::plugin::detail::PluginRegistrar<Derived, Base>                                \
      SERVOLOOP_PLUGIN_CONCAT(servoloop_plugin_registrar_, __COUNTER__){type_name};                \
  [[gnu::section("servoloop_plugin_index"), gnu::used]] constexpr auto SERVOLOOP_PLUGIN_CONCAT(   \
      servoloop_plugin_index_record_, __COUNTER__) =                                               \
      ::servoloop::plugin::detail::pluginIndexRecord<Base>(type_name);                             \
  }
