// `servoloop param ...` and `servoloop spawn-model` against a fake node.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

class ParamTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

TEST_F(ParamTest, LoadSendsTheAbsolutePathAndNamespace) {
  FakeNode node("/one_DOF_robot");
  const auto yaml = run_dir_.scratch() / "params.yaml";
  std::ofstream(yaml) << "a: 1\n";
  CliResult result = runCli({"param", "load", yaml.string()}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  result = runCli({"param", "load", yaml.string(), "/one_DOF_robot"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto loads = node.requestsFor("param.load");
  ASSERT_EQ(loads.size(), 2u);
  EXPECT_EQ(loads[0]["file"], yaml.string());
  EXPECT_EQ(loads[0]["namespace"], "/");
  EXPECT_EQ(loads[1]["namespace"], "/one_DOF_robot");
}

TEST_F(ParamTest, LoadOfAMissingFileNamesIt) {
  FakeNode node("/one_DOF_robot");
  const CliResult result = runCli({"param", "load", "/nonexistent/ctl.yaml"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("'/nonexistent/ctl.yaml' does not exist"));
  EXPECT_TRUE(node.requests().empty());
}

TEST_F(ParamTest, GetPrintsYamlOrJson) {
  FakeNode node("/one_DOF_robot");
  node.on("param.get", [](const json& request, auto&) -> json {
    if (request["name"] == "/one_DOF_robot/c/pid") return {{"value", {{"p", 10.0}, {"d", 1.5}}}};
    return {{"ok", false}, {"error", "no parameter '" + request["name"].get<std::string>() + "'"}};
  });
  CliResult result = runCli({"param", "get", "/one_DOF_robot/c/pid", "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out), json({{"p", 10.0}, {"d", 1.5}}));
  result = runCli({"param", "get", "c/pid", "-N", "/one_DOF_robot"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "d: 1.5\np: 10.0\n");
  result = runCli({"param", "get", "/one_DOF_robot/missing"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_EQ(result.err, "servoloop param get: error: no parameter '/one_DOF_robot/missing'\n");
}

TEST_F(ParamTest, SetSendsTheTextForTheNodeToType) {
  FakeNode node("/one_DOF_robot");
  ASSERT_EQ(runCli({"param", "set", "/one_DOF_robot/c/pid/p", "12.5"}, run_dir_.scratch()).status,
            0);
  const auto set = node.requestsFor("param.set").at(0);
  EXPECT_EQ(set["name"], "/one_DOF_robot/c/pid/p");
  EXPECT_EQ(set["value"], "12.5");
}

TEST_F(ParamTest, DumpPrintsOrWritesTheYaml) {
  FakeNode node("/one_DOF_robot");
  node.on("param.dump", [](const json&, auto&) -> json { return {{"yaml", "a: 1\nb: [1, 2]\n"}}; });
  CliResult result = runCli({"param", "dump", "/one_DOF_robot"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "a: 1\nb: [1, 2]\n");
  EXPECT_EQ(node.requestsFor("param.dump").at(0)["namespace"], "/one_DOF_robot");
  const auto file = run_dir_.scratch() / "dump.yaml";
  result = runCli({"param", "dump", "-o", file.string()}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(readFile(file), "a: 1\nb: [1, 2]\n");
  EXPECT_EQ(node.requestsFor("param.dump").at(1)["namespace"], "/");
}

TEST_F(ParamTest, ListTextAndJson) {
  FakeNode node("/one_DOF_robot");
  node.on("param.list", [](const json&, auto&) -> json {
    return {{"names", {"/one_DOF_robot/c/joint", "/one_DOF_robot/c/type"}}};
  });
  CliResult result = runCli({"param", "list", "/one_DOF_robot"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "/one_DOF_robot/c/joint\n/one_DOF_robot/c/type\n");
  result = runCli({"param", "list", "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out), json({"/one_DOF_robot/c/joint", "/one_DOF_robot/c/type"}));
}

TEST_F(ParamTest, SpawnModelGoesToTheWorldWithAbsolutePaths) {
  FakeNode world("/");
  FakeNode robot("/other_robot");
  world.on("model.spawn", [](const json&, auto&) -> json { return {{"namespace", "/one_DOF_robot"}}; });
  const std::string urdf =
      std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description_w_jnt_ctl.urdf";
  const std::string params = std::string(SERVOLOOP_SEED_DIR) + "/control_config/one_dof_ctl_params.yaml";
  const CliResult result = runCli(
      {"spawn-model", "--urdf", urdf, "--model", "one_DOF_robot", "--param", params},
      run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("Spawned model 'one_DOF_robot' in namespace /one_DOF_robot"));
  EXPECT_TRUE(robot.requests().empty());
  const auto spawn = world.requestsFor("model.spawn").at(0);
  EXPECT_EQ(spawn["urdf"], std::filesystem::absolute(urdf).lexically_normal().string());
  EXPECT_EQ(spawn["model"], "one_DOF_robot");
  EXPECT_FALSE(spawn.contains("namespace"));
  EXPECT_EQ(spawn["params"],
            json({std::filesystem::absolute(params).lexically_normal().string()}));
}

TEST_F(ParamTest, SpawnModelWithoutAWorldOrWithAMissingFile) {
  const std::string urdf =
      std::string(SERVOLOOP_SEED_DIR) + "/minimal_robot_description.urdf";
  CliResult result = runCli({"spawn-model", "--urdf", urdf, "--model", "m"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("no servoloop world is running"));
  result = runCli({"spawn-model", "--urdf", "/no/such.urdf", "--model", "m"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("--urdf file '/no/such.urdf' does not exist"));
  result = runCli({"spawn-model", "--urdf", urdf}, run_dir_.scratch());
  EXPECT_NE(result.status, 0);
  EXPECT_THAT(result.err, HasSubstr("--model"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

}  // namespace
}  // namespace servoloop::cli::testing
