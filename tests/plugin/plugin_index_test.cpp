// The plugin index: records the registration macro writes at compile time,
// read back from the built library files without loading them.
#include <algorithm>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "plugin_index_reader.hpp"

#include "temp_dir.hpp"

namespace servoloop::plugin {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::FieldsAre;

struct ExampleBase {
  static constexpr const char* kPluginKind = "robot_hw";
};

fs::path caseLibrary(const std::string& name) {
  return fs::path(SERVOLOOP_TEST_PLUGIN_DIR) / name / ("libfixture_" + name + ".so");
}

TEST(PluginIndex, RecordIsMagicVersionKindAndTypeEachNulTerminated) {
  constexpr auto record = detail::pluginIndexRecord<ExampleBase>("pkg/Type");
  const std::string expected = std::string("servoloop-plugin") + '\0' + std::to_string(kPluginApiVersion) +
                               '\0' + "robot_hw" + '\0' + "pkg/Type" + '\0';
  EXPECT_EQ(std::string(record.data(), record.size()), expected);
}

TEST(PluginIndex, ParsesRecordsPaddedApartAndSkipsBrokenOnes) {
  const auto a = detail::pluginIndexRecord<ExampleBase>("pkg/A");
  const auto b = detail::pluginIndexRecord<ExampleBase>("pkg/B");
  std::string section(a.data(), a.size());
  section += std::string(13, '\0');  // alignment or sanitizer padding
  section += std::string("servoloop-plugin") + '\0' + "x7" + '\0' + "controller" + '\0' + "bad/Version" + '\0';
  section += std::string("servoloop-plugin") + '\0' + "2" + '\0' + '\0' + "no/Kind" + '\0';
  section += std::string(b.data(), b.size());
  section += "servoloop-plugin";  // cut short
  const auto entries = parsePluginIndex(section);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_THAT(entries[0], FieldsAre(kPluginApiVersion, "robot_hw", "pkg/A"));
  EXPECT_THAT(entries[1], FieldsAre(kPluginApiVersion, "robot_hw", "pkg/B"));
}

TEST(PluginIndex, ReadsTheRecordsOfEveryRegistrationInABuiltLibrary) {
  // libfixture_good.so registers four classes from two source files.
  const auto index = readPluginIndex(caseLibrary("good"));
  ASSERT_TRUE(index.has_value());
  std::vector<std::string> types;
  for (const auto& entry : *index) {
    EXPECT_EQ(entry.api_version, kPluginApiVersion);
    types.push_back(entry.kind + " " + entry.type_name);
  }
  std::sort(types.begin(), types.end());
  EXPECT_THAT(types, ElementsAre("controller fixture/Alpha", "controller fixture/Beta",
                                 "controller fixture/ThrowingController", "robot_hw fixture/Robot"));
}

TEST(PluginIndex, FilesWithoutAnIndexAreNotPlugins) {
  EXPECT_FALSE(readPluginIndex(caseLibrary("not_a_plugin")).has_value());
  const servoloop::testing::TempDir temp("servoloop-plugin-index");
  servoloop::testing::writeFile(temp.path() / "empty.so", "");
  servoloop::testing::writeFile(temp.path() / "text.so", "hello");
  // An ELF header that claims more section headers than the file holds.
  std::string header(64, '\0');
  header.replace(0, 4, "\x7f" "ELF");
  header[4] = 2;  // 64-bit
  header[5] = 1;  // little-endian
  header[16] = 3;  // ET_DYN
  header[18] = 62;  // x86-64
  header[58] = 64;  // e_shentsize
  header[60] = 100;  // e_shnum
  header[40] = 64;  // e_shoff
  servoloop::testing::writeFile(temp.path() / "truncated.so", header);
  EXPECT_FALSE(readPluginIndex(temp.path() / "empty.so").has_value());
  EXPECT_FALSE(readPluginIndex(temp.path() / "text.so").has_value());
  EXPECT_FALSE(readPluginIndex(temp.path() / "truncated.so").has_value());
  EXPECT_FALSE(readPluginIndex(temp.path() / "missing.so").has_value());
}

}  // namespace
}  // namespace servoloop::plugin
