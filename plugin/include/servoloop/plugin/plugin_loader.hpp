#pragma once
// Finds plugin libraries on a search path, checks their handshake, and creates
// objects from them. Non-real-time: used by the service thread and the command
// line, never by the control loop.
//
// Discovery runs no plugin code: the loader reads each library's plugin index
// (plugin_index.hpp) from the file. A library is dlopen'ed, and its handshake
// checked, only when one of its types is first created; a library that fails
// then fails that creation alone, with an error naming the file. Files on the
// path that carry no plugin index are not plugins and are passed over quietly.
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <typeinfo>
#include <vector>

#include "servoloop/plugin/plugin_api.hpp"
#include "servoloop/plugin/plugin_path.hpp"

namespace servoloop::plugin {

namespace detail {
// One dlopen'ed library. dlclose runs when the last owner lets go: the loader's
// type table and every object created from the library each hold one reference.
class LoadedLibrary;
}  // namespace detail

// A type some library on the path provides.
struct PluginTypeInfo {
  std::string type;               // e.g. "effort_controllers/JointPositionController"
  std::string kind;               // the base class's kPluginKind, e.g. "controller"
  std::filesystem::path library;  // absolute path of the .so providing it
};

// Why one library (or a type in it) could not be used.
struct PluginDiagnostic {
  std::filesystem::path library;
  std::string reason;
  // "<library>: <reason>", the form logged and shown to users.
  std::string message() const;
};

// Deletes a plugin object with the deleter of the library that created it,
// then releases that library. Default-constructed, it deletes nothing.
class PluginDeleter {
 public:
  PluginDeleter() = default;
  PluginDeleter(void (*destroy)(void*), std::shared_ptr<detail::LoadedLibrary> library);

  // Takes the Base pointer create() handed out (Base* converts implicitly).
  void operator()(void* base_object) const;

 private:
  void (*destroy_)(void*) = nullptr;
  // Released right after the object is deleted (hence mutable).
  mutable std::shared_ptr<detail::LoadedLibrary> library_;
};

template <class Base>
using PluginPtr = std::unique_ptr<Base, PluginDeleter>;

class PluginLoader {
 public:
  // Scans pluginSearchPath(): SERVOLOOP_PLUGIN_PATH and the default folders.
  PluginLoader();
  // Scans exactly these directories, in order (use pluginSearchPath(dirs) to
  // add the environment and default folders).
  explicit PluginLoader(std::vector<std::filesystem::path> search_directories);
  ~PluginLoader();

  PluginLoader(const PluginLoader&) = delete;
  PluginLoader& operator=(const PluginLoader&) = delete;

  // Creates an object of a registered type, using its library's factory.
  // The library stays loaded until the returned object is deleted. Throws
  // servoloop::Error when the type is unknown (naming the known types of that
  // kind, or where it looked when there are none), when it is registered under
  // another kind or base class, or when its constructor throws.
  template <class Base>
  PluginPtr<Base> create(const std::string& type) {
    const Created created = createErased(type, Base::kPluginKind, typeid(Base).name());
    return PluginPtr<Base>(static_cast<Base*>(created.base_object), created.deleter);
  }

  // Registered types, sorted by type name; all kinds when kind is empty. Read
  // from the libraries' plugin indexes: loads nothing.
  std::vector<PluginTypeInfo> listTypes(const std::string& kind = "") const;
  bool hasType(const std::string& type) const;

  // Everything that went wrong: libraries whose index was refused while
  // scanning (wrong API version, unreadable), type names provided twice, and
  // libraries that failed when they were loaded. Each is also logged once as
  // a warning. Cleared by reload().
  std::vector<PluginDiagnostic> diagnostics() const;

  const std::vector<std::filesystem::path>& searchDirectories() const { return search_directories_; }

  // Objects created by this loader that are not yet deleted.
  std::size_t liveObjectCount() const;

  // Forgets every library and scans the search path again, picking up new or
  // rebuilt libraries. Throws servoloop::Error while objects are alive unless
  // force is set; with force, libraries with live objects stay mapped until
  // those objects are deleted (so a rebuilt copy of such a library is not seen).
  void reload(bool force = false);

  // Forgets every library (each one is unloaded once no object needs it).
  // Same rule about live objects as reload().
  void unloadAll(bool force = false);

 private:
  struct Created {
    void* base_object;
    PluginDeleter deleter;
  };
  // A type from a library's index; entry and library are set once the
  // library is loaded.
  struct RegisteredType {
    PluginTypeInfo info;
    std::string base_type_id;
    const ServoloopPluginEntry* entry = nullptr;
    std::shared_ptr<detail::LoadedLibrary> library;
  };

  Created createErased(const std::string& type, const char* kind, const char* base_type_id);
  void scanLocked();
  void indexLibraryLocked(const std::filesystem::path& path);
  // Loads the library and binds its types' entries; throws servoloop::Error
  // naming the library when it cannot be loaded or fails its handshake.
  void loadLibraryLocked(const std::filesystem::path& path);
  void addDiagnosticLocked(const std::filesystem::path& library, std::string reason);
  void ensureNoLiveObjectsLocked(const char* action) const;
  std::string describeSearchPathLocked() const;

  std::vector<std::filesystem::path> search_directories_;
  mutable std::mutex mutex_;
  std::vector<RegisteredType> types_;  // sorted by type name
  std::vector<std::shared_ptr<detail::LoadedLibrary>> libraries_;
  std::vector<PluginDiagnostic> diagnostics_;
  std::map<std::filesystem::path, std::string> failed_libraries_;  // path -> why it failed to load
  std::set<std::string> logged_messages_;  // so a rescan does not repeat warnings
  std::shared_ptr<std::atomic<std::size_t>> live_objects_;
};

}  // namespace servoloop::plugin
