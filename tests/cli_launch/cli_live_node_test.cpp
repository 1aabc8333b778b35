// The client commands against a real node: `servoloop launch` of the seed on
// the mock backend in real time (serving its socket), then `servoloop plot
// --topic`, `topic list` and, once it has ended, the "no node" error — each
// bounded in time, on a private SERVOLOOP_RUN_DIR; and control, param and topic
// commands against a node on the wall clock; control gains; spawn-model's warnings.
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kSeedLaunch =
    (fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml").string();
const char* const kJointStates = "/one_DOF_robot/joint_states";

// Waits until the node answers `topic list` (it serves its socket once its
// robot is spawned); false after timeout_s.
bool waitForNode(const fs::path& scratch, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (runCli({"topic", "list"}, scratch, 10.0).status == 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

// Milliseconds as the shortest decimal text: 20 -> "0.02", 3000 -> "3.0".
std::string millisecondsText(long long ms) {
  std::string fraction = std::to_string(ms % 1000);
  fraction.insert(0, 3 - fraction.size(), '0');
  while (fraction.size() > 1 && fraction.back() == '0') fraction.pop_back();
  return std::to_string(ms / 1000) + "." + fraction;
}

TEST(CliLiveNode, PlotOfALiveTopicThenTopicListThenNoNodeAfterSigint) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  CliProcess launch({"launch", kSeedLaunch, "--backend", "mock"}, scratch);
  ASSERT_TRUE(waitForNode(scratch, 60.0)) << launch.currentOut();

  // One wall second of joint states at 50 Hz of simulated time, paced at
  // real time: about 50 rows (a loaded machine may lag behind).
  const fs::path png = scratch / "live.png";
  const fs::path csv_dir = scratch / "recorded";
  const CliResult plot = runCli({"plot", "--topic", kJointStates, "--duration", "1", "-o", png.string(),
                                 "--save-csv", csv_dir.string()},
                                scratch, 30.0);
  ASSERT_EQ(plot.status, 0) << plot.err;
  EXPECT_EQ(readFile(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::istringstream csv(readFile(csv_dir / "one_DOF_robot_joint_states.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time,joint1.position,joint1.velocity,joint1.effort");
  std::vector<double> stamps;
  while (std::getline(csv, line)) {
    const std::string time_text = line.substr(0, line.find(','));
    const double time_s = std::stod(time_text);
    // A multiple of 20 ms, printed as that decimal.
    const long long ms = std::llround(time_s * 1000.0);
    EXPECT_EQ(ms % 20, 0) << line;
    EXPECT_EQ(time_text, millisecondsText(ms)) << line;
    if (!stamps.empty()) {
      EXPECT_NEAR(time_s - stamps.back(), 0.02, 1e-12) << "lost a message before " << line;
    }
    stamps.push_back(time_s);
  }
  EXPECT_GE(stamps.size(), 10u);
  EXPECT_LE(stamps.size(), 80u);

  // One node: its topics, without a node column.
  const CliResult list = runCli({"topic", "list"}, scratch, 30.0);
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("/one_DOF_robot/joint_states  "));
  EXPECT_THAT(list.out, HasSubstr("sensor_msgs/JointState\n"));
  EXPECT_THAT(list.out, ::testing::Not(HasSubstr("node /one_DOF_robot")));

  launch.signal(SIGINT);
  const CliResult launched = launch.wait(30.0);
  ASSERT_FALSE(launched.timed_out);
  EXPECT_EQ(launched.status, 0) << launched.err;

  // The node left its lock file; the commands still say plainly that no node runs.
  EXPECT_TRUE(fs::exists(run_dir.runDir() / "one_DOF_robot.lock"));
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"topic", "list"}, std::vector<std::string>{"control", "list"}}) {
    const CliResult result = runCli(command, scratch, 30.0);
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(lineCount(result.err), 1) << result.err;
    EXPECT_THAT(result.err, HasSubstr("error: no servoloop node is running"));
  }
}

// The same commands against a robot on the wall clock (the mock standing in
// for hardware, `--clock wall`): the node serves them while its loop keeps
// its deadlines.
TEST(CliLiveNode, ClientCommandsAgainstAWallClockNode) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  CliProcess launch({"launch", kSeedLaunch, "--backend", "mock", "--clock", "wall"}, scratch);
  ASSERT_TRUE(waitForNode(scratch, 60.0)) << launch.currentOut();

  CliResult list = runCli({"control", "list"}, scratch, 30.0);
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("joint1_position_controller"));
  EXPECT_THAT(list.out, HasSubstr("running"));

  const CliResult param = runCli({"param", "get", "/one_DOF_robot/joint1_position_controller/type"}, scratch, 30.0);
  ASSERT_EQ(param.status, 0) << param.err;
  EXPECT_THAT(param.out, HasSubstr("effort_controllers/JointPositionController"));

  const CliResult pub = runCli({"topic", "pub", "/one_DOF_robot/joint1_position_controller/command",
                                "std_msgs/Float64", "0.5"},
                               scratch, 30.0);
  ASSERT_EQ(pub.status, 0) << pub.err;
  const CliResult echo = runCli({"topic", "echo", "-n", "2", "--json", kJointStates}, scratch, 30.0);
  ASSERT_EQ(echo.status, 0) << echo.err;
  EXPECT_EQ(lineCount(echo.out), 2) << echo.out;
  EXPECT_THAT(echo.out, HasSubstr("\"joint1\""));

  const CliResult stop = runCli({"control", "switch", "--stop", "joint1_position_controller"}, scratch, 30.0);
  ASSERT_EQ(stop.status, 0) << stop.err;
  list = runCli({"control", "list"}, scratch, 30.0);
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, ::testing::ContainsRegex("joint1_position_controller[^\n]*stopped"));

  launch.signal(SIGINT);
  const CliResult launched = launch.wait(30.0);
  ASSERT_FALSE(launched.timed_out);
  EXPECT_EQ(launched.status, 0) << launched.err;
  EXPECT_THAT(launched.err, HasSubstr("runs on the wall clock at 1000 Hz"));
}

// `control gains` against a running node: the seed's PID as its YAML gives it
// (robots/one_dof/control_config/one_dof_ctl_params.yaml), a change the
// running controller takes (its state topic reports the gains its updates
// use) and the parameters follow; bad requests are refused naming the fix.
TEST(CliLiveNode, ControlGainsShowsAndChangesARunningControllersPid) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  CliProcess launch({"launch", kSeedLaunch, "--backend", "mock", "--clock", "wall"}, scratch);
  ASSERT_TRUE(waitForNode(scratch, 60.0)) << launch.currentOut();
  const std::string controller = "joint1_position_controller";

  CliResult gains = runCli({"control", "gains", controller, "--json"}, scratch, 30.0);
  ASSERT_EQ(gains.status, 0) << gains.err;
  const nlohmann::json seed = nlohmann::json::parse(R"([{"name": "pid", "p": 10.0, "i": 10.0, "d": 10.0,
      "i_clamp_min": -10.0, "i_clamp_max": 10.0, "antiwindup": false}])");
  EXPECT_EQ(nlohmann::json::parse(gains.out), seed);

  gains = runCli({"control", "gains", controller, "--p", "42.5", "--d", "0.5", "--antiwindup", "true"}, scratch, 30.0);
  ASSERT_EQ(gains.status, 0) << gains.err;
  EXPECT_EQ(gains.out, controller + "/pid: p 42.5 i 10 d 0.5 i_clamp_min -10 i_clamp_max 10 antiwindup true\n");

  // The controller's state (every 10th update) reports the gains its update used.
  bool taken = false;
  for (int attempt = 0; attempt < 20 && !taken; ++attempt) {
    const CliResult state =
        runCli({"topic", "echo", "-n", "1", "--json", "/one_DOF_robot/" + controller + "/state"}, scratch, 30.0);
    ASSERT_EQ(state.status, 0) << state.err;
    const nlohmann::json message = nlohmann::json::parse(state.out);
    taken = message.value("p", 0.0) == 42.5 && message.value("d", 0.0) == 0.5 && message.value("antiwindup", false);
  }
  EXPECT_TRUE(taken);
  const CliResult param = runCli({"param", "get", "/one_DOF_robot/" + controller + "/pid/p"}, scratch, 30.0);
  ASSERT_EQ(param.status, 0) << param.err;
  EXPECT_THAT(param.out, HasSubstr("42.5"));

  const CliResult unknown = runCli({"control", "gains", controller, "--pid", "gains/joint1", "--p", "1"}, scratch, 30.0);
  EXPECT_EQ(unknown.status, 1);
  EXPECT_THAT(unknown.err, HasSubstr("no PID 'gains/joint1'; its PIDs are 'pid'"));
  const CliResult clamp = runCli({"control", "gains", controller, "--i-clamp-min", "5"}, scratch, 30.0);
  EXPECT_EQ(clamp.status, 1);
  EXPECT_THAT(clamp.err, HasSubstr("i_clamp_min <= 0 <= i_clamp_max"));
  const CliResult none = runCli({"control", "gains", "joint_state_controller", "--p", "1"}, scratch, 30.0);
  EXPECT_EQ(none.status, 1);
  EXPECT_THAT(none.err, HasSubstr("has no PID"));
  EXPECT_EQ(lineCount(none.err), 1) << none.err;
  // Nothing of the refused requests was taken.
  gains = runCli({"control", "gains", controller, "--json"}, scratch, 30.0);
  ASSERT_EQ(gains.status, 0) << gains.err;
  EXPECT_EQ(nlohmann::json::parse(gains.out)[0]["p"], 42.5);
  EXPECT_EQ(nlohmann::json::parse(gains.out)[0]["i_clamp_min"], -10.0);

  launch.signal(SIGINT);
  const CliResult launched = launch.wait(30.0);
  ASSERT_FALSE(launched.timed_out);
  EXPECT_EQ(launched.status, 0) << launched.err;
}

// `spawn-model` into a running world shows what the node warned about while
// spawning — here the hopper (tests/assets/features/hopper.urdf) spawned at
// z = 0.3 with its foot 0.25 m in the floor — not only the node's log.
// `servoloop world ...` against a node launched paced in real time: a paused
// world stands (two steps of 10 add exactly 20 physics steps), a running
// world refuses to step, and a reset brings it back to t = 0, still paused.
TEST(CliLiveNode, WorldPauseStepResetAndUnpause) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  CliProcess launch({"launch", kSeedLaunch}, scratch);
  ASSERT_TRUE(waitForNode(scratch, 60.0)) << launch.currentOut();
  const std::regex state(R"((paused|running) at t = ([0-9.e+-]+) s \(([0-9]+) physics steps\))");
  const auto steps = [&](const CliResult& result) -> long long {
    std::smatch match;
    if (!std::regex_search(result.out, match, state)) return -1;
    return std::stoll(match[3].str());
  };

  const CliResult refused = runCli({"world", "step", "5"}, scratch, 30.0);
  EXPECT_NE(refused.status, 0);
  EXPECT_THAT(refused.err, HasSubstr("pause it first"));

  const CliResult paused = runCli({"world", "pause"}, scratch, 30.0);
  ASSERT_EQ(paused.status, 0) << paused.err;
  EXPECT_THAT(paused.out, HasSubstr("paused at t ="));
  const long long at_pause = steps(paused);
  ASSERT_GT(at_pause, 0);
  EXPECT_EQ(steps(runCli({"world", "step", "10"}, scratch, 30.0)), at_pause + 10);
  EXPECT_EQ(steps(runCli({"world", "step", "10"}, scratch, 30.0)), at_pause + 20);
  EXPECT_EQ(steps(runCli({"world", "state"}, scratch, 30.0)), at_pause + 20) << "a paused world stands";

  // Gazebo's model services: the arm's state (a fixed base at its spawn
  // pose), its joint moved; an unknown joint refused by name.
  const CliResult model = runCli({"model", "get", "one_DOF_robot"}, scratch, 30.0);
  ASSERT_EQ(model.status, 0) << model.err;
  EXPECT_THAT(model.out, HasSubstr("one_DOF_robot (/one_DOF_robot), fixed base"));
  EXPECT_THAT(model.out, HasSubstr("position:    [0, 0, 0]"));
  EXPECT_THAT(runCli({"model", "list"}, scratch, 30.0).out, HasSubstr("one_DOF_robot (/one_DOF_robot)"));
  EXPECT_EQ(runCli({"model", "set-configuration", "one_DOF_robot", "--joint", "joint1=0.7"}, scratch, 30.0).status, 0);
  const CliResult unknown = runCli({"model", "set-configuration", "one_DOF_robot", "--joint", "elbow=0.7"}, scratch, 30.0);
  EXPECT_NE(unknown.status, 0);
  EXPECT_THAT(unknown.err, HasSubstr("elbow"));

  const CliResult reset = runCli({"world", "reset"}, scratch, 30.0);
  ASSERT_EQ(reset.status, 0) << reset.err;
  EXPECT_THAT(reset.out, HasSubstr("paused at t = 0 s (0 physics steps)"));
  const CliResult running = runCli({"world", "unpause"}, scratch, 30.0);
  EXPECT_THAT(running.out, HasSubstr("running at t ="));
  EXPECT_NE(runCli({"world", "step", "0"}, scratch, 30.0).status, 0) << "0 steps is refused";
}

TEST(CliLiveNode, SpawnModelShowsTheWarningsOfTheSpawn) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  const fs::path world = scratch / "floor.launch.yaml";
  std::ofstream(world) << "world: {ground_plane: true}\n";
  CliProcess launch({"launch", world.string()}, scratch);
  const std::string hopper = (fs::path(SERVOLOOP_SOURCE_DIR) / "tests" / "assets" / "features" / "hopper.urdf").string();
  CliResult spawn;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {  // until the world serves its socket
    spawn = runCli({"spawn-model", "--urdf", hopper, "--model", "hopper", "-z", "0.3"}, scratch, 30.0);
    if (spawn.status == 0 || spawn.err.find("no servoloop world is running") == std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (std::chrono::steady_clock::now() < deadline);
  ASSERT_EQ(spawn.status, 0) << spawn.err << launch.currentOut();
  EXPECT_THAT(spawn.out, HasSubstr("Spawned model 'hopper' in namespace /hopper"));
  EXPECT_THAT(spawn.err, HasSubstr("warning: " + hopper + ": link 'foot' starts 0.250 m below the ground plane"));
  EXPECT_THAT(spawn.err, HasSubstr("a root z of at least 0.550 m"));
  EXPECT_EQ(lineCount(spawn.err), 1) << spawn.err;

  // Standing on its foot: nothing to say.
  const CliResult standing =
      runCli({"spawn-model", "--urdf", hopper, "--model", "hopper2", "-x", "2", "-z", "0.6"}, scratch, 30.0);
  ASSERT_EQ(standing.status, 0) << standing.err;
  EXPECT_EQ(standing.err, "");

  launch.signal(SIGINT);
  const CliResult launched = launch.wait(30.0);
  ASSERT_FALSE(launched.timed_out);
  EXPECT_EQ(launched.status, 0) << launched.err;
}

// `servoloop model set|delete` on a world of two free boxes: the world's own
// socket serves the world and model commands although there are two robots;
// a box teleported on a paused world is where `model get` finds it, a NaN is
// refused, and a deleted box is gone (from the list, with its socket) while
// the other stays.
TEST(CliLiveNode, ModelSetTeleportsAndModelDeleteRemovesOneOfTwoModels) {
  ScopedRunDir run_dir;
  const fs::path& scratch = run_dir.scratch();
  std::ofstream(scratch / "box.urdf") << R"(<robot name="box"><link name="box">
  <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>)";
  const fs::path world = scratch / "boxes.launch.yaml";
  std::ofstream(world) << "world: {ground_plane: true}\nrobots:\n"
                          "  - {urdf: box.urdf, model: crate, namespace: /crate, pose: [0, 0, 0.1, 0, 0, 0]}\n"
                          "  - {urdf: box.urdf, model: pallet, namespace: /pallet, pose: [1, 0, 0.1, 0, 0, 0]}\n";
  CliProcess launch({"launch", world.string()}, scratch);
  CliResult paused;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {  // until the world serves its socket
    paused = runCli({"world", "pause"}, scratch, 30.0);
    if (paused.status == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (std::chrono::steady_clock::now() < deadline);
  ASSERT_EQ(paused.status, 0) << paused.err << launch.currentOut();

  const CliResult set = runCli({"model", "set", "crate", "--pose", "0.5", "-0.25", "2", "--twist", "0", "0", "1"},
                               scratch, 30.0);
  ASSERT_EQ(set.status, 0) << set.err;
  EXPECT_THAT(set.out, HasSubstr("position:    [0.5, -0.25, 2]"));
  EXPECT_THAT(set.out, HasSubstr("linear:      [0, 0, 1]"));
  const CliResult got = runCli({"model", "get", "crate"}, scratch, 30.0);
  EXPECT_THAT(got.out, HasSubstr("position:    [0.5, -0.25, 2]")) << "a paused world keeps the pose set";
  const CliResult nan = runCli({"model", "set", "crate", "--pose", "0", "nan", "1"}, scratch, 30.0);
  EXPECT_NE(nan.status, 0);
  EXPECT_THAT(nan.err, HasSubstr("finite"));

  const CliResult deleted = runCli({"model", "delete", "pallet"}, scratch, 30.0);
  ASSERT_EQ(deleted.status, 0) << deleted.err;
  EXPECT_THAT(deleted.out, HasSubstr("deleted /pallet"));
  const CliResult listed = runCli({"model", "list"}, scratch, 30.0);
  EXPECT_THAT(listed.out, HasSubstr("crate (/crate)"));
  EXPECT_THAT(listed.out, ::testing::Not(HasSubstr("pallet")));
  EXPECT_NE(runCli({"control", "list", "-N", "/pallet"}, scratch, 30.0).status, 0) << "its socket is closed";
  const CliResult again = runCli({"model", "delete", "pallet"}, scratch, 30.0);
  EXPECT_NE(again.status, 0);
  EXPECT_THAT(again.err, HasSubstr("no model 'pallet' in this world (it has: /crate)"));
  EXPECT_EQ(runCli({"world", "unpause"}, scratch, 30.0).status, 0);

  launch.signal(SIGINT);
  const CliResult launched = launch.wait(30.0);
  ASSERT_FALSE(launched.timed_out);
  EXPECT_EQ(launched.status, 0) << launched.err;
}

}  // namespace
}  // namespace servoloop::cli::testing
