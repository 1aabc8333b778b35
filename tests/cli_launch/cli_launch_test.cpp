// `servoloop launch … --duration 2 --json` and `servoloop plot`, run as child
// processes: the JSON summary, the CSV recordings, the PNG, and the one-line
// errors of bad flags.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kOneDof = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";
const std::string kSeedLaunch = (kOneDof / "one_dof_w_jnt_ctl.launch.yaml").string();

using servoloop::testing::readFile;

struct CliResult {
  int status = -1;
  std::string out;
  std::string err;
};

class CliLaunch : public ::testing::Test {
 protected:
  // Runs `servoloop <args>` (shell words) in the test's folder with a private
  // run directory and the build's own plugin folder, bounded in time.
  CliResult run(const std::string& args) {
    const auto result = servoloop::testing::runShell(
        std::string("exec '") + SERVOLOOP_CLI_EXE + "' " + args,
        {dir_, dir_, {{"SERVOLOOP_PLUGIN_PATH", std::nullopt}, {"SERVOLOOP_RUN_DIR", dir_.string()}}}, 300.0);
    EXPECT_FALSE(result.timed_out) << args;
    return {result.status, result.out, result.err};
  }

  static int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

  servoloop::testing::TempDir temp_{"servoloop-cli-launch"};
  fs::path dir_ = temp_.path();
};

TEST_F(CliLaunch, HeadlessRunPrintsJsonSummaryRecordsAndPlots) {
  const CliResult result =
      run("launch '" + kSeedLaunch +
          "' --backend mock --duration 2 --json --pub /one_DOF_robot/joint1_position_controller/command:=1.0@0.5"
          " --record /one_DOF_robot/joint_states=js.csv"
          " --record /one_DOF_robot/joint1_position_controller/command=cmd.csv --plot out/one_dof.png");
  ASSERT_EQ(result.status, 0) << result.err;

  // stdout is exactly one JSON object.
  ASSERT_EQ(lines(result.out), 1) << result.out;
  const json summary = json::parse(result.out);
  EXPECT_NEAR(summary["sim_time"].get<double>(), 2.0, 1e-9);
  EXPECT_EQ(summary["cycles"], 2000);
  EXPECT_GT(summary["wall_time"].get<double>(), 0.0);
  EXPECT_GT(summary["real_time_factor"].get<double>(), 1.0);  // free-running by default with --duration
  ASSERT_EQ(summary["robots"].size(), 1u);
  const json& robot = summary["robots"][0];
  EXPECT_EQ(robot["namespace"], "/one_DOF_robot");
  EXPECT_EQ(robot["backend"], "mock");
  ASSERT_EQ(robot["controllers"].size(), 2u);
  EXPECT_EQ(robot["controllers"][0]["name"], "joint_state_controller");
  EXPECT_EQ(robot["controllers"][0]["state"], "running");
  EXPECT_EQ(robot["controllers"][1]["name"], "joint1_position_controller");
  EXPECT_EQ(robot["controllers"][1]["state"], "running");
  EXPECT_EQ(robot["joints"][0]["name"], "joint1");
  // Commanded at 0.5 s and held near the URDF's 0.5 rad/s velocity limit (the
  // effort limiting lets it overshoot a little): in the remaining 1.5 s it has
  // moved, but got nowhere near the 1.0 rad command (0.75 rad at 0.5 rad/s).
  const double position = robot["joints"][0]["position"].get<double>();
  EXPECT_GT(position, 0.1);
  EXPECT_LT(position, 0.8);
  EXPECT_EQ(robot["loop"]["cycles"], 2000);
  EXPECT_GT(robot["loop"]["compute"]["max"].get<double>(), 0.0);

  // Recordings.
  std::stringstream joint_states(readFile(dir_ / "js.csv"));
  std::string line;
  std::getline(joint_states, line);
  EXPECT_EQ(line, "time,joint1.position,joint1.velocity,joint1.effort");
  int rows = 0;
  while (std::getline(joint_states, line)) ++rows;
  EXPECT_EQ(rows, 100);  // 2 s at 50 Hz: t = 0, 0.02, ..., 1.98
  EXPECT_EQ(readFile(dir_ / "cmd.csv"), "time,data\n0.5,1.0\n");

  // The plot: a PNG file (its 8-byte signature).
  const std::string png = readFile(dir_ / "out" / "one_dof.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(CliLaunch, PublicationAtTimeZeroIsRecordedAtZeroAndActsFromTheFirstStep) {
  const CliResult result =
      run("launch '" + kSeedLaunch +
          "' --backend mock --duration 0.1 --pub /one_DOF_robot/joint1_position_controller/command:=1.0"
          " --record /one_DOF_robot/joint1_position_controller/command=cmd.csv"
          " --record /one_DOF_robot/joint_states=js.csv");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(readFile(dir_ / "cmd.csv"), "time,data\n0.0,1.0\n");
  // Joint states from t = 0 (the start position, before any physics step),
  // then every 20 ms, stamps printed as the decimals they are.
  std::stringstream joint_states(readFile(dir_ / "js.csv"));
  std::string line;
  std::getline(joint_states, line);
  std::vector<std::string> times;
  while (std::getline(joint_states, line)) times.push_back(line.substr(0, line.find(',')));
  EXPECT_EQ(times, (std::vector<std::string>{"0.0", "0.02", "0.04", "0.06", "0.08"}));
  EXPECT_EQ(readFile(dir_ / "js.csv").find("\n0.0,0.0,0.0,"), readFile(dir_ / "js.csv").find('\n'));
}

// A trajectory from the command line: `--pub` on a trajectory controller's
// command topic takes the topic's type (trajectory_msgs/JointTrajectory) with
// no type given. The controller's desired position ends on the trajectory's
// last point, and the joint follows it (stiffness 500 N·m/rad against at most
// 4.2 N·m of gravity on the seed's arm: within 0.01 rad).
TEST_F(CliLaunch, PubFlagTakesTheTypeOfATrajectoryControllersTopic) {
  std::ofstream(dir_ / "traj.yaml") << R"(traj:
  type: effort_controllers/JointTrajectoryController
  joints: [joint1]
  gains: {joint1: {p: 500.0, i: 0.0, d: 10.0}}
)";
  std::ofstream(dir_ / "traj.launch.yaml") << "robots:\n  - urdf: '"
                                           << (kOneDof / "minimal_robot_description_w_jnt_ctl.urdf").string()
                                           << "'\n    params: [{file: traj.yaml, ns: /one_DOF_robot}]\n"
                                              "    controllers: [traj]\n";
  const CliResult result =
      run("launch traj.launch.yaml --duration 4 --json --record /one_DOF_robot/traj/state=state.csv"
          " --pub '/one_DOF_robot/traj/command:={joint_names: [joint1], points: [{positions: [0.6], "
          "time_from_start: 2.0}]}'");
  ASSERT_EQ(result.status, 0) << result.err;
  const json summary = json::parse(result.out);
  EXPECT_NEAR(summary["robots"][0]["joints"][0]["position"].get<double>(), 0.6, 0.01) << result.out;
  std::stringstream state(readFile(dir_ / "state.csv"));
  std::string header;
  std::string line;
  std::string last;
  std::getline(state, header);
  while (std::getline(state, line)) last = line;
  const std::vector<std::string> names = [&] {
    std::vector<std::string> columns;
    std::stringstream row(header);
    for (std::string cell; std::getline(row, cell, ',');) columns.push_back(cell);
    return columns;
  }();
  const auto desired = std::find(names.begin(), names.end(), "desired.positions[0]");
  ASSERT_NE(desired, names.end()) << header;
  std::stringstream row(last);
  std::string cell;
  for (auto it = names.begin(); it != desired + 1; ++it) std::getline(row, cell, ',');
  EXPECT_DOUBLE_EQ(std::stod(cell), 0.6) << header << "\n" << last;
}

TEST_F(CliLaunch, TextSummaryByDefault) {
  const CliResult result = run("launch '" + kSeedLaunch + "' --backend mock --duration 0.5");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("simulated 0.500 s"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("controller joint1_position_controller (effort_controllers/JointPositionController): running"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("joint joint1: position"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("500 cycles"), std::string::npos) << result.out;
  // stderr is not a terminal here: no progress bar.
  EXPECT_EQ(result.err.find('\r'), std::string::npos);
}

TEST_F(CliLaunch, PlotCommandDrawsRecordedCsv) {
  std::ofstream(dir_ / "js.csv") << "time,joint1.position,joint1.velocity,joint1.effort\n"
                                 << "0.0,0.0,0.0,0.0\n0.02,0.01,0.5,2.0\n0.04,0.02,0.5,1.5\n";
  std::ofstream(dir_ / "cmd.csv") << "time,data\n0.0,1.0\n";
  const CliResult result = run("plot js.csv cmd.csv -o plot.png");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(readFile(dir_ / "plot.png").substr(0, 4), "\x89PNG");
  const CliResult columns = run("plot js.csv -o columns.png --columns joint1.velocity");
  ASSERT_EQ(columns.status, 0) << columns.err;
  EXPECT_TRUE(fs::exists(dir_ / "columns.png"));
}

struct BadFlags {
  const char* args;
  const char* expected;  // in the one stderr line
};

class CliLaunchBadFlags : public CliLaunch, public ::testing::WithParamInterface<BadFlags> {};

TEST_P(CliLaunchBadFlags, ExitNonZeroWithOneLine) {
  std::string args = GetParam().args;
  const std::string placeholder = "SEED";
  if (const auto at = args.find(placeholder); at != std::string::npos) args.replace(at, placeholder.size(), "'" + kSeedLaunch + "'");
  const CliResult result = run(args);
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lines(result.err), 1) << result.err;
  EXPECT_NE(result.err.find(GetParam().expected), std::string::npos) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
}

INSTANTIATE_TEST_SUITE_P(
    Flags, CliLaunchBadFlags,
    ::testing::Values(BadFlags{"launch no_such.launch.yaml", "no_such.launch.yaml"},
                      BadFlags{"launch SEED --duration -1", "--duration"},
                      BadFlags{"launch SEED --rtf fast", "--rtf"},
                      BadFlags{"launch SEED --duration 1 --pub /a/command=1.0", "expected TOPIC[:TYPE]:=VALUE[@TIME]"},
                      BadFlags{"launch SEED --duration 1 --record /a/joint_states", "expected TOPIC=FILE.csv"},
                      BadFlags{"launch SEED --duration 1 --plot x.png", "nothing is recorded"},
                      BadFlags{"launch SEED --duration 1 --backend warp", "backend 'warp'"},
                      BadFlags{"plot missing.csv -o x.png", "missing.csv"}));

TEST_F(CliLaunch, BadLaunchFileKeyIsOneLine) {
  std::ofstream(dir_ / "bad.launch.yaml") << "world:\n  backend: mock\n  timestep: 0.001\n";
  const CliResult result = run("launch bad.launch.yaml --duration 1");
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lines(result.err), 1) << result.err;
  EXPECT_NE(result.err.find("bad.launch.yaml:3:3: world.timestep: unknown key 'timestep'"), std::string::npos)
      << result.err;
}

// A xacro robot: its launch file's xacro_args reach the expansion, a bad one
// is one error naming the xacro file and line, and `servoloop xacro` and
// `check-urdf` take the same file with name:=value arguments.
const std::string kXacroRobot =
    (fs::path(SERVOLOOP_SOURCE_DIR) / "tests" / "assets" / "xacro" / "two_wheel_arm.urdf.xacro").string();

TEST_F(CliLaunch, XacroRobotRunsWithItsLaunchFileArguments) {
  std::ofstream(dir_ / "xacro.launch.yaml") << "world: {backend: mock}\nrobots:\n  - urdf: '" << kXacroRobot
                                             << "'\n    xacro_args: {arm_length: 0.6}\n";
  CliResult result = run("launch xacro.launch.yaml --duration 0.05 --json");
  ASSERT_EQ(result.status, 0) << result.err;
  const json summary = json::parse(result.out);
  std::vector<std::string> joints;
  for (const auto& joint : summary.at("robots").at(0).at("joints")) joints.push_back(joint.at("name"));
  EXPECT_EQ(joints, (std::vector<std::string>{"arm_joint", "left_wheel_joint", "right_wheel_joint"}));

  // The argument is used in ${arm_length / 2} on line 47 of the xacro file.
  std::ofstream(dir_ / "bad.launch.yaml") << "world: {backend: mock}\nrobots:\n  - urdf: '" << kXacroRobot
                                           << "'\n    xacro_args: {arm_length: long}\n";
  result = run("launch bad.launch.yaml --duration 0.05");
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lines(result.err), 1) << result.err;
  EXPECT_NE(result.err.find(kXacroRobot + ":47: xacro: ${arm_length / 2}: unsupported operand types for /: str"),
            std::string::npos)
      << result.err;
}

TEST_F(CliLaunch, XacroCommandAndCheckUrdfTakeNameColonEqualsArguments) {
  CliResult result = run("xacro '" + kXacroRobot + "' arm_length:=0.6 -o arm.urdf");
  ASSERT_EQ(result.status, 0) << result.err;
  const std::string urdf = readFile(dir_ / "arm.urdf");
  // The arm's mass is 2 kg/m times its length (0.6 m): 1.2 kg.
  EXPECT_NE(urdf.find(R"(<mass value="1.2"/>)"), std::string::npos) << urdf;
  EXPECT_EQ(urdf.find("xacro:"), std::string::npos) << "nothing of xacro is left";

  result = run("check-urdf '" + kXacroRobot + "' arm_length:=0.6");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("robot name is: two_wheel_arm"), std::string::npos) << result.out;

  result = run("check-urdf '" + kXacroRobot + "' arm_length=0.6");
  EXPECT_NE(result.status, 0);
  EXPECT_EQ(lines(result.err), 1) << result.err;
  EXPECT_NE(result.err.find("'arm_length=0.6' is not name:=value"), std::string::npos) << result.err;
}

// The seed's ROS launch file runs unchanged, to the same result as its YAML
// counterpart (same robot, controllers and trajectory, bit for bit).
TEST_F(CliLaunch, SeedRosLaunchFileRunsAsItsYamlCounterpart) {
  const std::string flags =
      "' --backend mock --duration 1.5 --json --pub /one_DOF_robot/joint1_position_controller/command:=1.0@0.5";
  const CliResult xml = run("launch '" + (kOneDof / "minimal_robot_w_jnt_ctl.launch").string() + flags);
  ASSERT_EQ(xml.status, 0) << xml.err;
  const CliResult yaml = run("launch '" + kSeedLaunch + flags);
  ASSERT_EQ(yaml.status, 0) << yaml.err;
  json a = json::parse(xml.out)["robots"][0];
  json b = json::parse(yaml.out)["robots"][0];
  // Update times are measured (they differ); their counts are not.
  for (json* run : {&a, &b}) {
    for (json& controller : (*run)["controllers"]) {
      EXPECT_GT(controller["update_time"]["count"].get<std::uint64_t>(), 0u);
      controller["update_time"] = controller["update_time"]["count"];
    }
  }
  EXPECT_EQ(a["namespace"], "/one_DOF_robot");
  EXPECT_EQ(a["controllers"], b["controllers"]);
  EXPECT_EQ(a["joints"], b["joints"]);
  EXPECT_GT(a["joints"][0]["position"].get<double>(), 0.1) << "the command moved the joint";

  // name:=value arguments belong to ROS launch files only.
  const CliResult args = run("launch '" + kSeedLaunch + "' use_gui:=false --duration 0.1");
  EXPECT_NE(args.status, 0);
  EXPECT_EQ(lines(args.err), 1) << args.err;
  EXPECT_NE(args.err.find("name:=value arguments (use_gui:=false) are for ROS .launch files"), std::string::npos)
      << args.err;
}

// Numbers a command line cannot mean, and files that are no files, are one
// line each naming the option or path and what it accepts; nothing hangs.
TEST_F(CliLaunch, OutOfRangeNumbersAndDevicesAreOneLineErrors) {
  struct Case {
    std::string args;
    std::string error;
  };
  const std::vector<Case> cases = {
      {"launch '" + kSeedLaunch + "' --duration inf", "--duration: inf is outside 0 to 1e+09 (simulated seconds)"},
      {"launch '" + kSeedLaunch + "' --duration 1e300", "--duration: 1e300 is outside 0 to 1e+09"},
      {"launch '" + kSeedLaunch + "' --duration nan", "--duration: nan is outside"},
      {"launch '" + kSeedLaunch + "' --rtf -1", "--rtf: -1 is outside 0 to 1e+06"},
      {"launch '" + kSeedLaunch + "' --duration ten", "--duration: 'ten' is not a number"},
      {"spawner --timeout nan joint_state_controller", "--timeout: nan is outside 0 to 1e+09"},
      {"topic pub -r inf /x std_msgs/Float64 1", "--rate: inf is outside 1e-06 to 1e+06 (messages per second)"},
      {"check-urdf /dev/zero", "/dev/zero: is not a regular file (a device, FIFO or socket)"},
      {"launch /dev/zero --duration 1", "/dev/zero: is not a regular file"},
      {"plot wide.csv -o wide.png", "the plot would draw 5000 lines; one plot draws at most 64"},
      {"fly", "servoloop: error: unknown command 'fly'; the commands are: launch, "},
      {"control fly", "servoloop control: error: unknown command 'fly'; the commands are: list-types, "},
  };
  {
    std::ofstream wide(dir_ / "wide.csv");
    wide << "time";
    for (int c = 0; c < 5000; ++c) wide << ",c" << c;
    wide << "\n0";
    for (int c = 0; c < 5000; ++c) wide << ",1.0";
    wide << "\n";
  }
  for (const Case& c : cases) {
    const CliResult result = run(c.args);
    EXPECT_NE(result.status, 0) << c.args;
    EXPECT_EQ(lines(result.err), 1) << c.args << ": " << result.err;
    EXPECT_NE(result.err.find(c.error), std::string::npos) << c.args << ": " << result.err;
  }
}

// servoloop's capsule arm is launched as franka_gazebo launches the Panda
// (tests/assets/xacro/launch/capsule_arm.launch): xacro with string methods
// and YAML dicts, one transmission per interface without reductions, the
// controller YAML with $(arg arm_id) in it, start positions, a spawner
// waiting with --wait-for. The two controllers of a vendor's own types fail
// with the usual message and make the launch fail; the rest runs: the
// trajectory controller holds the arm at its start position.
TEST_F(CliLaunch, LaunchFileWrittenAsFrankaGazebosRunsAllButTheVendorsControllers) {
  const std::string launch =
      (fs::path(SERVOLOOP_SOURCE_DIR) / "tests/assets/xacro/launch/capsule_arm.launch").string();
  const CliResult result = run("launch '" + launch +
                               "' controller:=position_joint_trajectory_controller --backend mock --duration 1 --json");
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.err.find("load controller 'capsule_state_controller': unknown controller type "
                            "'capsule_control/CapsuleStateController'"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("load controller 'capsule_gripper': unknown controller type "
                            "'capsule_gazebo/CapsuleGripperSim'"),
            std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.find("'initialized'"), std::string::npos) << "--wait-for's topic is no controller: " << result.err;
  EXPECT_NE(result.err.find("2 joints have one SimpleTransmission per hardware interface"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("actuators capsule_joint1_motor, capsule_joint2_motor, capsule_finger_joint_motor without "
                            "<mechanicalReduction> are taken as a direct drive"),
            std::string::npos)
      << result.err;

  const json robot = json::parse(result.out)["robots"][0];
  EXPECT_EQ(robot["launch_failures"], json({"controller 'capsule_gripper' did not load",
                                            "controller 'capsule_state_controller' did not load"}));
  ASSERT_EQ(robot["controllers"].size(), 1u);
  EXPECT_EQ(robot["controllers"][0]["name"], "position_joint_trajectory_controller");
  EXPECT_EQ(robot["controllers"][0]["state"], "running");
  ASSERT_EQ(robot["joints"].size(), 3u);
  const std::vector<std::pair<std::string, double>> start = {
      {"capsule_finger_joint", 0.01}, {"capsule_joint1", 0.3}, {"capsule_joint2", -0.5}};
  for (std::size_t i = 0; i < start.size(); ++i) {
    EXPECT_EQ(robot["joints"][i]["name"], start[i].first);
    EXPECT_NEAR(robot["joints"][i]["position"].get<double>(), start[i].second, 1e-9) << start[i].first;
  }
}

}  // namespace
