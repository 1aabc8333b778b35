#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "servoloop/plugin/plugin_path.hpp"

namespace servoloop::plugin {
namespace {

namespace fs = std::filesystem;

TEST(PluginPath, SplitsColonSeparatedListsDroppingEmptyEntries) {
  EXPECT_EQ(splitPluginPath("/a:/b/c"), (std::vector<fs::path>{"/a", "/b/c"}));
  EXPECT_EQ(splitPluginPath("::/a::/b:"), (std::vector<fs::path>{"/a", "/b"}));
  EXPECT_TRUE(splitPluginPath("").empty());
}

// Sets an environment variable for one test and restores it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) setenv(name, value, 1); else unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) setenv(name_, old_->c_str(), 1); else unsetenv(name_);
  }
 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(PluginPath, DefaultFolderIsLibServoloopPluginsNextToTheExecutable) {
  // This test binary lives in <build>/bin, like the servoloop command line.
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  const auto dirs = defaultPluginDirectories();
  ASSERT_FALSE(dirs.empty());
  EXPECT_EQ(dirs.front(), (exe_dir.parent_path() / "lib" / "servoloop" / "plugins").lexically_normal());
}

TEST(PluginPath, SearchOrderIsExplicitThenEnvironmentThenDefaultWithoutDuplicates) {
  ScopedEnv env(kPluginPathEnvVar, "/env/one:/explicit/a:/env/two");
  const auto dirs = pluginSearchPath({"/explicit/a", "/explicit/b/"});
  const auto defaults = defaultPluginDirectories();
  ASSERT_EQ(dirs.size(), 4 + defaults.size());
  EXPECT_EQ(dirs[0], fs::path("/explicit/a"));
  EXPECT_EQ(dirs[1], fs::path("/explicit/b"));
  EXPECT_EQ(dirs[2], fs::path("/env/one"));
  EXPECT_EQ(dirs[3], fs::path("/env/two"));
  EXPECT_EQ(dirs[4], defaults.front());
}

TEST(PluginPath, RelativeEntriesAreResolvedAgainstTheCurrentDirectory) {
  ScopedEnv env(kPluginPathEnvVar, "relative/plugins:./relative/plugins");
  const auto dirs = pluginSearchPath();
  const fs::path expected = fs::current_path() / "relative" / "plugins";
  EXPECT_EQ(dirs.front(), expected);
  // "./relative/plugins" is the same directory and is kept once.
  EXPECT_EQ(std::count(dirs.begin(), dirs.end(), expected), 1);
}

TEST(PluginPath, UnsetEnvironmentAddsNothing) {
  ScopedEnv env(kPluginPathEnvVar, nullptr);
  EXPECT_TRUE(pluginPathFromEnvironment().empty());
  EXPECT_EQ(pluginSearchPath(), defaultPluginDirectories());
}

}  // namespace
}  // namespace servoloop::plugin
