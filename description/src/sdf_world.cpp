// SDFormat worlds (sdf_world.hpp): which paths are world files, and reading
// one through the module that links libsdformat (sdf_reader/), loaded on the
// first world file a process reads.
#include "servoloop/description/sdf_world.hpp"

#include <dlfcn.h>

#include <mutex>
#include <string>

#include <fmt/format.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/executable_path.hpp"

namespace servoloop {
namespace fs = std::filesystem;

namespace {

using ReadSdfWorldFunction = void (*)(const fs::path&, SdfWorld&);

// Address inside this library, for loadedObjectDirectory.
void sdfWorldAnchor() {}

// The module beside this library: <libdir>/servoloop/libservoloop_sdf_reader.so,
// in the build tree as in an install.
fs::path sdfReaderModulePath() {
  std::error_code error;
  const fs::path library_dir = loadedObjectDirectory(reinterpret_cast<const void*>(&sdfWorldAnchor), error);
  if (error) throw Error("cannot find where libservoloop_description is loaded from, to find its SDF reader");
  return library_dir / "servoloop" / "libservoloop_sdf_reader.so";
}

ReadSdfWorldFunction loadSdfReader() {
  static std::once_flag once;
  static ReadSdfWorldFunction reader = nullptr;
  static std::string failure;
  std::call_once(once, [] {
    const fs::path module = sdfReaderModulePath();
    // Never closed: libsdformat stays loaded for the rest of the process.
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      failure = fmt::format("reading SDF worlds needs {} (built and installed with servoloop), which cannot be "
                            "loaded: {}; rebuild or reinstall servoloop",
                            module.string(), why != nullptr ? why : "no reason given");
      return;
    }
    reader = reinterpret_cast<ReadSdfWorldFunction>(dlsym(handle, "servoloop_read_sdf_world"));
    if (reader == nullptr) {
      failure = fmt::format("{} has no servoloop_read_sdf_world; it is not servoloop's SDF reader: reinstall servoloop",
                            module.string());
    }
  });
  if (reader == nullptr) throw Error(failure);
  return reader;
}

}  // namespace

bool isSdfWorldPath(const fs::path& path) {
  const std::string extension = path.extension().string();
  return extension == ".world" || extension == ".sdf";
}

SdfWorld readSdfWorld(const fs::path& file) {
  SdfWorld world;
  loadSdfReader()(file, world);
  return world;
}

}  // namespace servoloop
