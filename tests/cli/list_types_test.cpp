// `servoloop control list-types` run as a child process, against the fixture
// plugins of tests/controller_manager/fixtures.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using servoloop::testing::lineCount;
using servoloop::testing::readFile;
using CliResult = servoloop::testing::ProcessResult;

// Runs `servoloop <args>` (shell words) with SERVOLOOP_PLUGIN_PATH set to
// plugin_path (unset when empty), capturing both streams in a private folder.
CliResult runServoloop(const std::string& args, const std::string& plugin_path = "") {
  const servoloop::testing::TempDir scratch("servoloop-list-types");
  std::optional<std::string> path;
  if (!plugin_path.empty()) path = plugin_path;
  return servoloop::testing::runShell(std::string("exec '") + SERVOLOOP_CLI_EXE + "' " + args,
                                      {scratch.path(), {}, {{"SERVOLOOP_PLUGIN_PATH", path}}}, 60.0);
}

fs::path caseDir(const std::string& name) { return fs::path(SERVOLOOP_TEST_PLUGIN_DIR) / name; }
std::string caseLibrary(const std::string& name) {
  return fs::canonical(caseDir(name) / ("libfixture_" + name + ".so")).string();
}

TEST(ListTypes, PrintsATableOfTypeKindAndLibrary) {
  const CliResult result = runServoloop("control list-types", caseDir("good").string());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("TYPE"));
  const std::string library = caseLibrary("good");
  // Columns are padded to the longest type and kind on the whole plugin path
  // (the build's real plugins are listed too), so check alignment, not widths.
  std::istringstream lines(result.out);
  std::string header, line;
  std::getline(lines, header);
  const std::size_t kind_column = header.find("KIND");
  const std::size_t library_column = header.find("LIBRARY");
  ASSERT_NE(kind_column, std::string::npos) << header;
  ASSERT_NE(library_column, std::string::npos) << header;
  std::map<std::string, std::string> row_of_type;
  while (std::getline(lines, line)) row_of_type[line.substr(0, line.find(' '))] = line;
  for (const auto& [type, kind] : {std::pair<std::string, std::string>{"fixture/Alpha", "controller"},
                                   {"fixture/Robot", "robot_hw"}}) {
    ASSERT_EQ(row_of_type.count(type), 1u) << result.out;
    const std::string& row = row_of_type[type];
    EXPECT_EQ(row.substr(kind_column, kind.size()), kind) << row;
    EXPECT_EQ(row.substr(library_column), library) << row;
  }
  EXPECT_THAT(result.err, Not(HasSubstr(library)));
}

TEST(ListTypes, JsonIsAnArrayOfTypeKindLibrary) {
  const CliResult result = runServoloop("control list-types --json", caseDir("good").string());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto types = nlohmann::json::parse(result.out);
  ASSERT_TRUE(types.is_array());
  // Other plugins of this build may be listed too; look at the fixture's.
  std::map<std::string, std::string> fixture_kinds;
  for (const auto& type : types) {
    ASSERT_TRUE(type.contains("type") && type.contains("kind") && type.contains("library"));
    if (type["library"] == caseLibrary("good")) fixture_kinds[type["type"]] = type["kind"];
  }
  EXPECT_EQ(fixture_kinds, (std::map<std::string, std::string>{
                               {"fixture/Alpha", "controller"},
                               {"fixture/Beta", "controller"},
                               {"fixture/Robot", "robot_hw"},
                               {"fixture/ThrowingController", "controller"}}));
}

TEST(ListTypes, KindFilterAndPluginDirFlag) {
  const CliResult result = runServoloop(
      "control list-types --json --kind robot_hw --plugin-dir '" + caseDir("good").string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const auto types = nlohmann::json::parse(result.out);
  bool found_robot = false;
  for (const auto& type : types) {
    EXPECT_EQ(type["kind"], "robot_hw");
    found_robot = found_robot || type["type"] == "fixture/Robot";
  }
  EXPECT_TRUE(found_robot);
}

TEST(ListTypes, ListingReadsPluginIndexesAndRunsNoPluginCode) {
  // One library aborts in its static constructor, one cannot be linked, one
  // fails the ABI handshake, one is from another plugin API version, one is
  // not a plugin at all. Listing loads none of them (exit 0, not 134): it
  // reads their plugin indexes. Only the refused index is a warning.
  const std::string path = caseDir("not_a_plugin").string() + ":" + caseDir("wrong_api_version").string() + ":" +
                           caseDir("wrong_abi_size").string() + ":" + caseDir("undefined_symbol").string() + ":" +
                           caseDir("aborting_constructor").string() + ":" + caseDir("good").string();
  const CliResult result = runServoloop("control list-types", path);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("fixture/Beta"));
  EXPECT_THAT(result.out, HasSubstr("fixture/AbortsWhenLoaded"));
  EXPECT_THAT(result.out, HasSubstr("fixture/NeedsMissingSymbol"));
  EXPECT_THAT(result.out, HasSubstr("fixture/WrongAbiSize"));
  EXPECT_THAT(result.out, Not(HasSubstr("fixture/FromAnotherVersion")));
  EXPECT_THAT(result.err, HasSubstr(caseLibrary("wrong_api_version") + ": wrong plugin API version"));
  EXPECT_THAT(result.err, Not(HasSubstr("not_a_plugin")));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  // Warnings never reach stdout, so --json output stays parseable.
  const CliResult json = runServoloop("control list-types --json", path);
  EXPECT_TRUE(nlohmann::json::accept(json.out)) << json.out;
}

TEST(ListTypes, HelpIsAvailableAtEveryLevel) {
  for (const std::string args : {"--help", "control --help", "control list-types --help"}) {
    const CliResult result = runServoloop(args);
    EXPECT_EQ(result.status, 0) << args << ": " << result.err;
    EXPECT_THAT(result.out, HasSubstr("Usage")) << args;
  }
  EXPECT_THAT(runServoloop("control list-types --help").out, HasSubstr("--json"));
  EXPECT_THAT(runServoloop("--help").out, HasSubstr("control"));
}

TEST(ListTypes, UsageErrorsAreOneLineOnStderrWithNonZeroStatus) {
  const CliResult bad_dir = runServoloop("control list-types --plugin-dir /no/such/servoloop/dir");
  EXPECT_NE(bad_dir.status, 0);
  EXPECT_EQ(lineCount(bad_dir.err), 1) << bad_dir.err;
  EXPECT_THAT(bad_dir.err, HasSubstr("/no/such/servoloop/dir"));
  EXPECT_EQ(bad_dir.out, "");

  const CliResult no_subcommand = runServoloop("control");
  EXPECT_NE(no_subcommand.status, 0);
  EXPECT_EQ(lineCount(no_subcommand.err), 1) << no_subcommand.err;
  EXPECT_THAT(no_subcommand.err, HasSubstr("servoloop control --help"));

  const CliResult unknown_flag = runServoloop("control list-types --jsn");
  EXPECT_NE(unknown_flag.status, 0);
  EXPECT_EQ(lineCount(unknown_flag.err), 1) << unknown_flag.err;
  EXPECT_THAT(unknown_flag.err, HasSubstr("--jsn"));
}

}  // namespace
