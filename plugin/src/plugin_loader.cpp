#include "servoloop/plugin/plugin_loader.hpp"

#include <cxxabi.h>
#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <system_error>
#include <utility>

#include "servoloop/core/errors.hpp"
#include "plugin_index_reader.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::plugin {
namespace fs = std::filesystem;

namespace detail {

class LoadedLibrary {
 public:
  LoadedLibrary(fs::path path, void* handle,
                std::shared_ptr<std::atomic<std::size_t>> loader_live_objects)
      : path_(std::move(path)), handle_(handle), loader_live_objects_(std::move(loader_live_objects)) {}
  ~LoadedLibrary() { dlclose(handle_); }

  LoadedLibrary(const LoadedLibrary&) = delete;
  LoadedLibrary& operator=(const LoadedLibrary&) = delete;

  const fs::path& path() const { return path_; }
  void* handle() const { return handle_; }
  void objectCreated() { loader_live_objects_->fetch_add(1); }
  void objectDestroyed() { loader_live_objects_->fetch_sub(1); }

 private:
  fs::path path_;
  void* handle_;
  // Shared with the loader, which may be gone before the last object is.
  std::shared_ptr<std::atomic<std::size_t>> loader_live_objects_;
};

}  // namespace detail

namespace {

std::string demangle(const char* mangled) {
  int status = 0;
  char* readable = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
  if (status != 0 || readable == nullptr) return mangled;
  std::string result(readable);
  std::free(readable);
  return result;
}

// dlerror() text usually starts with the library path, which the diagnostic
// already shows.
std::string dlopenReason(const fs::path& path, const char* error_text) {
  std::string text = error_text ? error_text : "unknown dlopen error";
  const std::string prefix = path.string() + ": ";
  if (text.rfind(prefix, 0) == 0) text.erase(0, prefix.size());
  return "cannot be loaded (dlopen): " + text;
}

bool isPluginFileName(const fs::path& path) {
  const std::string name = path.filename().string();
  return name.size() > 6 && name.rfind("lib", 0) == 0 && path.extension() == ".so";
}

std::string joinTypeNames(const std::vector<PluginTypeInfo>& types) {
  std::string names;
  for (const auto& type : types) names += (names.empty() ? "" : ", ") + type.type;
  return names;
}

}  // namespace

std::string PluginDiagnostic::message() const { return library.string() + ": " + reason; }

PluginDeleter::PluginDeleter(void (*destroy)(void*),
                             std::shared_ptr<detail::LoadedLibrary> library)
    : destroy_(destroy), library_(std::move(library)) {}

void PluginDeleter::operator()(void* base_object) const {
  if (base_object == nullptr || destroy_ == nullptr) return;
  destroy_(base_object);
  if (library_ == nullptr) return;
  library_->objectDestroyed();
  // Let go of the library now rather than when the owning pointer goes away;
  // this may dlclose it, which is safe because no plugin code is on the stack.
  library_.reset();
}

PluginLoader::PluginLoader() : PluginLoader(pluginSearchPath()) {}

PluginLoader::PluginLoader(std::vector<fs::path> search_directories)
    : search_directories_(std::move(search_directories)),
      live_objects_(std::make_shared<std::atomic<std::size_t>>(0)) {
  std::lock_guard lock(mutex_);
  scanLocked();
}

PluginLoader::~PluginLoader() = default;

std::vector<PluginTypeInfo> PluginLoader::listTypes(const std::string& kind) const {
  std::lock_guard lock(mutex_);
  std::vector<PluginTypeInfo> result;
  for (const auto& type : types_) {
    if (kind.empty() || type.info.kind == kind) result.push_back(type.info);
  }
  return result;
}

bool PluginLoader::hasType(const std::string& type) const {
  std::lock_guard lock(mutex_);
  return std::any_of(types_.begin(), types_.end(),
                     [&](const RegisteredType& registered) { return registered.info.type == type; });
}

std::vector<PluginDiagnostic> PluginLoader::diagnostics() const {
  std::lock_guard lock(mutex_);
  return diagnostics_;
}

std::size_t PluginLoader::liveObjectCount() const { return live_objects_->load(); }

void PluginLoader::reload(bool force) {
  std::lock_guard lock(mutex_);
  // Forced, objects still alive keep their own library mapped.
  if (!force) ensureNoLiveObjectsLocked("reload plugin libraries");
  types_.clear();
  libraries_.clear();
  diagnostics_.clear();
  failed_libraries_.clear();
  scanLocked();
}

void PluginLoader::unloadAll(bool force) {
  std::lock_guard lock(mutex_);
  if (!force) ensureNoLiveObjectsLocked("unload plugin libraries");
  types_.clear();
  libraries_.clear();
  diagnostics_.clear();
  failed_libraries_.clear();
}

void PluginLoader::ensureNoLiveObjectsLocked(const char* action) const {
  const std::size_t live = live_objects_->load();
  if (live == 0) return;
  throw Error("cannot " + std::string(action) + ": " + std::to_string(live) +
              " object(s) created from them still exist; unload those controllers/backends "
              "first, or force it");
}

PluginLoader::Created PluginLoader::createErased(const std::string& type, const char* kind,
                                                 const char* base_type_id) {
  const ServoloopPluginEntry* entry = nullptr;
  std::shared_ptr<detail::LoadedLibrary> library;
  {
    std::lock_guard lock(mutex_);
    const auto found = std::find_if(types_.begin(), types_.end(),
                                    [&](const RegisteredType& t) { return t.info.type == type; });
    if (found == types_.end()) {
      std::vector<PluginTypeInfo> known;
      for (const auto& t : types_) {
        if (t.info.kind == kind) known.push_back(t.info);
      }
      std::string message = "unknown " + std::string(kind) + " type '" + type + "'; ";
      if (known.empty()) {
        message += "no " + std::string(kind) + " plugins found in " + describeSearchPathLocked() +
                   " (add directories with " + kPluginPathEnvVar + ")";
      } else {
        message += "known " + std::string(kind) + " types: " + joinTypeNames(known);
      }
      if (!diagnostics_.empty()) {
        message += "; " + std::to_string(diagnostics_.size()) + " problem(s) while loading plugins:";
        for (const auto& diagnostic : diagnostics_) message += " [" + diagnostic.message() + "]";
      }
      throw Error(message);
    }
    if (found->info.kind != kind) {
      throw Error("plugin type '" + type + "' (" + found->info.library.string() + ") is a " +
                  found->info.kind + " plugin, not a " + kind + " plugin");
    }
    if (found->library == nullptr) {
      const fs::path path = found->info.library;
      try {
        loadLibraryLocked(path);
      } catch (const Error& error) {
        throw Error("cannot create plugin type '" + type + "': " + error.what());
      }
      if (found->entry == nullptr) {
        throw Error("cannot create plugin type '" + type + "': " + path.string() +
                    " lists it in its plugin index but does not register it when loaded; rebuild the "
                    "plugin (its index and its code disagree)");
      }
    }
    if (found->base_type_id != base_type_id) {
      throw Error("plugin type '" + type + "' (" + found->info.library.string() +
                  ") derives from " + demangle(found->base_type_id.c_str()) + ", not from " +
                  demangle(base_type_id) + "; both declare plugin kind '" + kind + "'");
    }
    entry = found->entry;
    library = found->library;
  }

  // The constructor runs without the lock: it may take time or use a loader itself.
  void* object = nullptr;
  try {
    object = entry->create();
  } catch (const std::exception& error) {
    throw Error("plugin type '" + type + "' (" + library->path().string() +
                "): constructor threw: " + error.what());
  }
  if (object == nullptr) {
    throw Error("plugin type '" + type + "' (" + library->path().string() +
                "): factory returned no object");
  }
  library->objectCreated();
  return Created{object, PluginDeleter(entry->destroy, std::move(library))};
}

// Why another user could put code into this process through `path`, or ""
// when none can: a file or folder every user may write to (a sticky folder
// such as /tmp still lets anyone add files), or, for a process running as
// root, one owned by an ordinary user. (Group-writable is left alone: with
// per-user groups, as Debian gives, it is the user's own.)
static std::string foreignWriteAccess(const fs::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return "";
  char mode[8];
  std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(info.st_mode & 07777));
  if ((info.st_mode & S_IWOTH) != 0) return std::string("it is writable by every user (mode ") + mode + ")";
  if (::geteuid() == 0 && info.st_uid != 0) {
    return "this process runs as root and it is owned by uid " + std::to_string(info.st_uid);
  }
  return "";
}

void PluginLoader::scanLocked() {
  std::vector<fs::path> seen;
  for (const auto& dir : search_directories_) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) continue;
    // A folder others can write to may gain a library at any time: its
    // libraries are not loaded (one warning says why and how to fix it).
    if (const std::string why = foreignWriteAccess(dir); !why.empty()) {
      addDiagnosticLocked(dir, "plugin folder not searched: " + why +
                                   ", so another user could place a library this process would run; make it "
                                   "writable only by its owner (chmod o-w), owned by root when root runs servoloop");
      continue;
    }
    std::vector<fs::path> candidates;
    for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
      if (isPluginFileName(it->path()) && fs::is_regular_file(it->path(), error)) {
        candidates.push_back(it->path());
      }
    }
    if (error) {
      addDiagnosticLocked(dir, "cannot list plugin directory: " + error.message());
      continue;
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& candidate : candidates) {
      const fs::path canonical = fs::weakly_canonical(candidate, error);
      const fs::path& path = error ? candidate : canonical;
      if (std::find(seen.begin(), seen.end(), path) != seen.end()) continue;
      seen.push_back(path);
      indexLibraryLocked(path);
    }
  }
}

void PluginLoader::indexLibraryLocked(const fs::path& path) {
  if (const std::string why = foreignWriteAccess(path); !why.empty()) {
    addDiagnosticLocked(path, "not loaded: " + why +
                                  ", so another user could change the code this process runs; make it writable "
                                  "only by its owner (chmod o-w), owned by root when root runs servoloop");
    return;
  }
  const auto index = readPluginIndex(path);
  if (!index) {
    // Any other library may share a folder with plugins: not worth a warning.
    logger().debug("plugin path: {} has no servoloop plugin index; not a plugin, ignored", path.string());
    return;
  }
  if (index->empty()) {
    addDiagnosticLocked(path, "its plugin index holds no readable record; rebuild the plugin against this "
                              "servoloop");
    return;
  }
  for (const auto& record : *index) {
    if (record.api_version != kPluginApiVersion) {
      addDiagnosticLocked(path, "wrong plugin API version: built for version " +
                                    std::to_string(record.api_version) + ", this servoloop loads version " +
                                    std::to_string(kPluginApiVersion) +
                                    "; rebuild the plugin against this servoloop");
      return;
    }
  }
  for (const auto& record : *index) {
    const std::string& type = record.type_name;
    const auto existing = std::lower_bound(
        types_.begin(), types_.end(), type,
        [](const RegisteredType& t, const std::string& name) { return t.info.type < name; });
    if (existing != types_.end() && existing->info.type == type) {
      if (existing->info.library == path) {
        addDiagnosticLocked(path, "type '" + type + "' is registered twice in this library; "
                                  "the second registration is ignored");
      } else {
        addDiagnosticLocked(path, "duplicate type '" + type + "': already provided by " +
                                      existing->info.library.string() +
                                      ", which comes first on the plugin path; this library's '" +
                                      type + "' is ignored (rename one of them or remove one "
                                      "library from the plugin path)");
      }
      continue;
    }
    types_.insert(existing, RegisteredType{PluginTypeInfo{type, record.kind, path}, {}, nullptr, nullptr});
  }
}

void PluginLoader::loadLibraryLocked(const fs::path& path) {
  if (const auto failed = failed_libraries_.find(path); failed != failed_libraries_.end()) {
    throw Error(path.string() + ": " + failed->second);
  }
  const auto refuse = [&](const std::string& reason) {
    failed_libraries_[path] = reason;
    addDiagnosticLocked(path, reason);
    throw Error(path.string() + ": " + reason);
  };

  dlerror();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) refuse(dlopenReason(path, dlerror()));
  auto library = std::make_shared<detail::LoadedLibrary>(path, handle, live_objects_);

  auto entry_point =
      reinterpret_cast<ServoloopPluginManifestFn>(dlsym(handle, kPluginEntryPointName));
  if (entry_point == nullptr) {
    refuse(std::string("not a servoloop plugin: no ") + kPluginEntryPointName +
           " entry point (register classes with SERVOLOOP_REGISTER_PLUGIN)");
  }
  const ServoloopPluginManifest* manifest = entry_point();
  if (manifest == nullptr) refuse(std::string(kPluginEntryPointName) + " returned no manifest");

  // The handshake, in the order the fields are stable: nothing else in the
  // manifest is read until the version and every size match.
  if (manifest->api_version != kPluginApiVersion) {
    refuse("wrong plugin API version: built for version " + std::to_string(manifest->api_version) +
           ", this servoloop loads version " + std::to_string(kPluginApiVersion) +
           "; rebuild the plugin against this servoloop");
  }
  if (manifest->abi_probe_size != kPluginAbiProbeSize ||
      manifest->abi_probe_align != kPluginAbiProbeAlign ||
      manifest->manifest_size != sizeof(ServoloopPluginManifest) ||
      manifest->entry_size != sizeof(ServoloopPluginEntry)) {
    refuse("ABI mismatch: the library's ABI probe has size " + std::to_string(manifest->abi_probe_size) +
           " and alignment " + std::to_string(manifest->abi_probe_align) + " (manifest " +
           std::to_string(manifest->manifest_size) + ", entry " + std::to_string(manifest->entry_size) +
           " bytes), this servoloop expects size " + std::to_string(kPluginAbiProbeSize) + " and alignment " +
           std::to_string(kPluginAbiProbeAlign) + " (manifest " + std::to_string(sizeof(ServoloopPluginManifest)) +
           ", entry " + std::to_string(sizeof(ServoloopPluginEntry)) +
           " bytes); rebuild the plugin with the same compiler, standard library and servoloop headers");
  }
  if (manifest->entry_count == 0) {
    refuse("plugin library registers no classes (is SERVOLOOP_REGISTER_PLUGIN in a source file that is "
           "linked into it?)");
  }

  for (std::uint32_t i = 0; i < manifest->entry_count; ++i) {
    const ServoloopPluginEntry& entry = manifest->entries[i];
    if (entry.kind == nullptr || entry.type_name == nullptr || entry.base_type_id == nullptr ||
        entry.create == nullptr || entry.destroy == nullptr) {
      addDiagnosticLocked(path, "manifest entry " + std::to_string(i) + " is incomplete; ignored");
      continue;
    }
    for (auto& registered : types_) {
      if (registered.info.library != path || registered.info.type != entry.type_name) continue;
      if (registered.info.kind != entry.kind) {
        addDiagnosticLocked(path, "type '" + registered.info.type + "' is a " + entry.kind +
                                      " plugin in its code but a " + registered.info.kind +
                                      " plugin in its index; rebuild the plugin");
        continue;
      }
      registered.entry = &entry;
      registered.base_type_id = entry.base_type_id;
      registered.library = library;
    }
  }
  libraries_.push_back(std::move(library));
}

void PluginLoader::addDiagnosticLocked(const fs::path& library, std::string reason) {
  PluginDiagnostic diagnostic{library, std::move(reason)};
  const std::string message = diagnostic.message();
  if (logged_messages_.insert(message).second) logger().warn("plugin {}", message);
  diagnostics_.push_back(std::move(diagnostic));
}

std::string PluginLoader::describeSearchPathLocked() const {
  if (search_directories_.empty()) return "an empty plugin search path";
  std::string description;
  for (const auto& dir : search_directories_) {
    std::error_code error;
    description += (description.empty() ? "" : ", ") + dir.string();
    if (!fs::is_directory(dir, error)) description += " (missing)";
  }
  return description;
}

}  // namespace servoloop::plugin
