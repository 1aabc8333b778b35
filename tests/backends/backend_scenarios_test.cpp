// Swapping the simulator is one flag: the same launch files run with
// `servoloop launch FILE --backend bullet|mujoco|mock` (the built executable,
// as a child process), and each run must end with every controller running
// and its joints at rest at the steady state worked out here by hand:
//
//  - integral action (the seed's PID, the arm's PIDs) removes every constant
//    load: the joints settle on their commands, whatever the gravity;
//  - a PD without integral settles where it balances gravity,
//    kp·(command − q) = ∂V/∂q (V the potential energy; at rest the
//    velocity terms vanish), solved below by Newton's method;
//  - mock has no gravity, so every controller reaches its command there.
//
// Then `servoloop compare` runs the seed PID scenario on bullet and mujoco and
// the differences must stay below bounds derived from the step size (see
// SeedPidBulletVsMujocoWithinTheFirstOrderBound and
// SeedPidToOneRadianThroughTheVelocityLimit).
#include <gtest/gtest.h>

#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kRobots = fs::path(SERVOLOOP_SOURCE_DIR) / "robots";
constexpr double kG = 9.81;

using servoloop::testing::readFile;

struct CliResult {
  int status = -1;
  std::string out;
  std::string err;
};

// A private folder per test; `servoloop` runs in it without SERVOLOOP_PLUGIN_PATH
// (the build's own plugin folder is found next to the executable), bounded in time.
class CliRun {
 public:
  CliResult run(const std::string& args) const {
    const auto result = servoloop::testing::runShell(
        std::string("exec '") + SERVOLOOP_CLI_EXE + "' " + args,
        {dir(), dir(), {{"SERVOLOOP_PLUGIN_PATH", std::nullopt}, {"SERVOLOOP_RUN_DIR", dir().string()}}},
        600.0);
    EXPECT_FALSE(result.timed_out) << args;
    return {result.status, result.out, result.err};
  }
  const fs::path& dir() const { return temp_.path(); }

 private:
  servoloop::testing::TempDir temp_{"servoloop-backends"};
};

bool backendBuilt(const std::string& backend) {
  if (backend == "mujoco") {
#ifdef SERVOLOOP_HAVE_MUJOCO
    return true;
#else
    return false;
#endif
  }
  if (backend == "bullet") {
#ifdef SERVOLOOP_HAVE_BULLET
    return true;
#else
    return false;
#endif
  }
  return true;
}

// ---------------------------------------------------------------------------
// Steady states
// ---------------------------------------------------------------------------

// The seed robot's link2 (both seed URDFs): 1 kg, centre of mass d = 0.5 m
// above joint1 at q = 0 (an inverted pendulum): V = m g d cos q, so
// ∂V/∂q = −m g d sin q.
constexpr double kSeedMgd = 1.0 * kG * 0.5;
double seedGravityGradient(double q) { return -kSeedMgd * std::sin(q); }

// The raw PD at rest: kp (cmd − q) = −m g d sin q, by Newton from q = cmd.
double seedRawPdEquilibrium(double kp, double command) {
  double q = command;
  for (int i = 0; i < 50; ++i) {
    const double f = kp * (command - q) - seedGravityGradient(q);
    const double df = -kp + kSeedMgd * std::cos(q);
    q -= f / df;
  }
  return q;
}

// robots/chain/chain.urdf: n links of length L and mass m hanging from the
// mount, centres of mass at L/2, all joints about y. With φ_k = q_1 + … + q_k
// the absolute angle of link k from the vertical, its centre of mass is
// L (cos φ_1 + … + cos φ_(k−1)) + (L/2) cos φ_k below the mount, so
//   V = −m g L Σ_k (n − k + ½) cos φ_k,  ∂V/∂φ_k = m g L (n − k + ½) sin φ_k,
//   ∂V/∂q_i = Σ_(k ≥ i) ∂V/∂φ_k,  ∂²V/∂q_i∂q_j = Σ_(k ≥ max(i, j)) m g L (n − k + ½) cos φ_k.
constexpr int kChainLinks = 6;
constexpr double kChainLinkLength = 0.25, kChainLinkMass = 0.5;

Eigen::VectorXd chainEquilibrium(const Eigen::VectorXd& kp, const Eigen::VectorXd& command) {
  const int n = kChainLinks;
  const double mgl = kChainLinkMass * kG * kChainLinkLength;
  Eigen::VectorXd q = command;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::VectorXd phi(n);
    double sum = 0.0;
    for (int k = 0; k < n; ++k) phi[k] = (sum += q[k]);
    // 1-based k in the formulas: weight (n − k + ½) for 0-based index k is n − k − ½.
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      for (int k = i; k < n; ++k) gradient[i] += mgl * (n - k - 0.5) * std::sin(phi[k]);
      for (int j = 0; j < n; ++j) {
        for (int k = std::max(i, j); k < n; ++k) hessian(i, j) += mgl * (n - k - 0.5) * std::cos(phi[k]);
      }
    }
    const Eigen::VectorXd residual = kp.cwiseProduct(command - q) - gradient;
    const Eigen::MatrixXd jacobian = -Eigen::MatrixXd(kp.asDiagonal()) - hessian;
    q -= jacobian.lu().solve(residual);
  }
  return q;
}

// ---------------------------------------------------------------------------
// Scenarios
// ---------------------------------------------------------------------------

struct Expected {
  std::vector<std::string> joints;
  std::vector<double> position;  // rad
  std::vector<double> effort;    // N·m; empty: not checked
};

struct Scenario {
  std::string name;
  fs::path launch;
  std::string flags;  // --pub ...
  double duration_s;
  std::vector<std::string> controllers;  // all must be running at the end
  std::function<Expected(const std::string& backend)> expected;
  double position_tolerance;  // rad
  double velocity_tolerance;  // rad/s
};

std::vector<Scenario> scenarios() {
  std::vector<Scenario> list;

  // The seed's PID (robots/one_dof/control_config/one_dof_ctl_params.yaml:
  // p 10, i 10, d 10, integral clamped at ±10 N·m) commanded to 1.0 rad. The
  // integral takes the gravity load m g d sin(1) = 4.13 N·m, well inside its
  // clamp and the 10 N·m effort limit, so q → 1.0 on every backend, holding
  // effort ∂V/∂q(1.0) = −4.13 N·m (the link leans past upright, gravity pulls
  // it further, the motor holds it back); 0 on mock. The approach is slow:
  // the URDF's 0.5 rad/s velocity limit, then the integral (time constant
  // p/i = 1 s) removes the rest; 30 s leave it settled to well under 1e-3 rad.
  list.push_back({"seed_pid", kRobots / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml",
                  "--pub /one_DOF_robot/joint1_position_controller/command:=1.0", 30.0,
                  {"joint_state_controller", "joint1_position_controller"},
                  [](const std::string& backend) {
                    const bool gravity = backend != "mock";
                    return Expected{{"joint1"}, {1.0}, {gravity ? seedGravityGradient(1.0) : 0.0}};
                  },
                  1e-3, 1e-3});

  // The tutorial's raw PD (kp 10, kv 3, at 100 Hz; no integral) to 1.0 rad.
  // kp and the command come from the YAML and the flag; gravity makes it
  // settle beyond the command: 10 (1 − q) = −4.905 sin q → q ≈ 1.49 rad.
  list.push_back({"seed_raw_pd", kRobots / "one_dof" / "one_dof_raw_pd.launch.yaml",
                  "--pub /one_DOF_robot/minimal_joint_controller/pos_cmd:=1.0", 10.0,
                  {"joint_state_controller", "minimal_joint_controller"},
                  [](const std::string& backend) {
                    const YAML::Node yaml = YAML::LoadFile(
                        (kRobots / "one_dof" / "control_config" / "minimal_joint_controller.yaml").string());
                    const double kp = yaml["one_DOF_robot"]["minimal_joint_controller"]["kp"].as<double>();
                    const double q = backend == "mock" ? 1.0 : seedRawPdEquilibrium(kp, 1.0);
                    return Expected{{"joint1"}, {q}, {kp * (1.0 - q)}};
                  },
                  1e-3, 1e-3});

  // The two-joint arm's PIDs (commands in its launch file): shoulder −0.6,
  // elbow 0.5 rad on every backend; the integral terms take the gravity load.
  list.push_back({"two_joint_arm", kRobots / "two_joint_arm" / "two_joint_arm.launch.yaml", "", 15.0,
                  {"joint_state_controller", "shoulder_position_controller", "elbow_position_controller"},
                  [](const std::string&) { return Expected{{"shoulder", "elbow"}, {-0.6, 0.5}, {}}; }, 1e-3, 1e-3});

  // The chain's PDs: gravity sag from the commands, solved from the YAML's kp
  // and the launch file's commands; on mock, the commands.
  // The chain's slowest mode decays at about 1.4 /s (see its YAML): 20 s.
  list.push_back({"chain", kRobots / "chain" / "chain.launch.yaml", "", 20.0,
                  {"joint_state_controller", "joint_1_position_controller", "joint_2_position_controller",
                   "joint_3_position_controller", "joint_4_position_controller", "joint_5_position_controller",
                   "joint_6_position_controller"},
                  [](const std::string& backend) {
                    const YAML::Node gains =
                        YAML::LoadFile((kRobots / "chain" / "control_config" / "chain_controllers.yaml").string());
                    const YAML::Node launch = YAML::LoadFile((kRobots / "chain" / "chain.launch.yaml").string());
                    Eigen::VectorXd kp(kChainLinks), command(kChainLinks);
                    Expected expected;
                    for (int k = 0; k < kChainLinks; ++k) {
                      const std::string controller = "joint_" + std::to_string(k + 1) + "_position_controller";
                      kp[k] = gains["chain"][controller]["pid"]["p"].as<double>();
                      command[k] = launch["publish"][k]["value"].as<double>();
                      EXPECT_EQ(launch["publish"][k]["topic"].as<std::string>(), "/chain/" + controller + "/command");
                      expected.joints.push_back("joint_" + std::to_string(k + 1));
                    }
                    const Eigen::VectorXd q = backend == "mock" ? command : chainEquilibrium(kp, command);
                    expected.position.assign(q.data(), q.data() + q.size());
                    return expected;
                  },
                  1e-3, 1e-3});
  return list;
}

struct Case {
  std::size_t scenario;
  std::string backend;
};

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  return scenarios()[info.param.scenario].name + "_" + info.param.backend;
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (std::size_t s = 0; s < scenarios().size(); ++s) {
    for (const char* backend : {"bullet", "mujoco", "mock"}) cases.push_back({s, backend});
  }
  return cases;
}

class BackendScenario : public ::testing::TestWithParam<Case> {};

TEST_P(BackendScenario, EndsWithEveryControllerRunningAtTheSteadyState) {
  const Scenario scenario = scenarios()[GetParam().scenario];
  const std::string& backend = GetParam().backend;
  if (!backendBuilt(backend)) GTEST_SKIP() << "the '" << backend << "' backend is not built here";

  CliRun cli;
  std::ostringstream args;
  args << "launch '" << scenario.launch.string() << "' --backend " << backend << " --duration "
       << scenario.duration_s << " --json " << scenario.flags;
  const CliResult result = cli.run(args.str());
  ASSERT_EQ(result.status, 0) << result.err;
  const json summary = json::parse(result.out);
  ASSERT_EQ(summary["robots"].size(), 1u);
  const json& robot = summary["robots"][0];
  EXPECT_EQ(robot["backend"], backend);
  EXPECT_NEAR(summary["sim_time"].get<double>(), scenario.duration_s, 1e-9);

  std::vector<std::string> running;
  for (const json& controller : robot["controllers"]) {
    EXPECT_EQ(controller["state"], "running") << controller.dump();
    running.push_back(controller["name"]);
  }
  EXPECT_EQ(running, scenario.controllers);

  const Expected expected = scenario.expected(backend);
  ASSERT_EQ(robot["joints"].size(), expected.joints.size()) << robot["joints"].dump();
  for (std::size_t j = 0; j < expected.joints.size(); ++j) {
    const auto found = std::find_if(robot["joints"].begin(), robot["joints"].end(),
                                    [&](const json& joint) { return joint["name"] == expected.joints[j]; });
    ASSERT_NE(found, robot["joints"].end()) << expected.joints[j] << " in " << robot["joints"].dump();
    const json& joint = *found;
    const double position = joint["position"].get<double>();
    std::printf("%s on %s: %s at %.6f rad (expected %.6f), velocity %.2e rad/s, effort %.4f N·m\n",
                scenario.name.c_str(), backend.c_str(), expected.joints[j].c_str(), position, expected.position[j],
                joint["velocity"].get<double>(), joint["effort"].get<double>());
    EXPECT_NEAR(position, expected.position[j], scenario.position_tolerance) << expected.joints[j];
    EXPECT_NEAR(joint["velocity"].get<double>(), 0.0, scenario.velocity_tolerance) << expected.joints[j];
    if (!expected.effort.empty()) {
      // The effort at rest follows from the position: 1e-3 rad of position
      // tolerance is at most kp·1e-3 = 0.01 N·m, plus the gravity term's share.
      EXPECT_NEAR(joint["effort"].get<double>(), expected.effort[j], 0.02) << expected.joints[j];
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, BackendScenario, ::testing::ValuesIn(allCases()), caseName);

// ---------------------------------------------------------------------------
// servoloop compare
// ---------------------------------------------------------------------------

// Largest |joint1.velocity| of a JointState recording (CSV of `launch --record`).
double maxSpeed(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,joint1.position,joint1.velocity,joint1.effort");
  double speed = 0.0;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string time, position, velocity;
    std::getline(row, time, ',');
    std::getline(row, position, ',');
    std::getline(row, velocity, ',');
    speed = std::max(speed, std::abs(std::stod(velocity)));
  }
  return speed;
}

const std::string kSeedPidCommand = "/one_DOF_robot/joint1_position_controller/command";

TEST(BackendCompare, SeedPidBulletVsMujocoWithinTheFirstOrderBound) {
  if (!backendBuilt("bullet") || !backendBuilt("mujoco")) GTEST_SKIP() << "needs the bullet and mujoco backends";
  // The bound, from the step dt = 1 ms (the derivation of tests/cross_engine):
  //  - MuJoCo integrates with RK4, global error O(dt⁴): for this slow loop
  //    (a few rad/s) far below 1e-5 rad; allow 1e-5;
  //  - Bullet integrates with semi-implicit Euler (v += a·dt, then q += v·dt),
  //    first order: per step its position moves dt·v_(k+1) where the exact
  //    motion moves dt·(v_k + v_(k+1))/2, a lead of dt·Δv/2 that in a stable,
  //    smooth closed loop does not build up beyond about dt·max|q̇|.
  //  Bound: dt·max|q̇| + 1e-5, max|q̇| measured on a bullet run.
  // "Smooth" matters: a 0.3 rad command keeps joint1 under its 0.5 rad/s URDF
  // velocity limit (asserted), so the effort saturation never switches.
  // (SeedPidToOneRadianThroughTheVelocityLimit covers the command of 1.0.)
  constexpr double kDt = 0.001;
  const std::string launch = (kRobots / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml").string();
  const std::string pub = " --pub " + kSeedPidCommand + ":=0.3";
  CliRun cli;
  const CliResult recorded = cli.run("launch '" + launch + "' --backend bullet --duration 10" + pub +
                                     " --record /one_DOF_robot/joint_states=js.csv");
  ASSERT_EQ(recorded.status, 0) << recorded.err;
  const double max_speed = maxSpeed(cli.dir() / "js.csv");
  ASSERT_LT(max_speed, 0.5) << "the premise: joint1 stays under its velocity limit";
  ASSERT_GT(max_speed, 0.1) << "the joint must move for the comparison to mean something";
  const double bound = kDt * max_speed + 1e-5;

  const CliResult result = cli.run("compare '" + launch + "' --backends bullet,mujoco --duration 10 --json" + pub +
                                   " --plot compare.png --tolerance " + std::to_string(bound));
  ASSERT_EQ(result.status, 0) << result.err << result.out;
  const json report = json::parse(result.out);
  EXPECT_EQ(report["backends"], json({"bullet", "mujoco"}));
  ASSERT_EQ(report["runs"].size(), 2u);
  for (const json& run : report["runs"]) {
    for (const json& controller : run["summary"]["robots"][0]["controllers"]) EXPECT_EQ(controller["state"], "running");
  }
  ASSERT_EQ(report["topics"].size(), 1u);
  const json& topic = report["topics"][0];
  EXPECT_EQ(topic["topic"], "/one_DOF_robot/joint_states");
  EXPECT_EQ(topic["samples"], 500);  // 10 s at 50 Hz, the same stamps on both
  EXPECT_EQ(topic["max_stamp_offset"], 0.0);
  const json& joint = topic["joints"][0];
  EXPECT_EQ(joint["name"], "joint1");
  EXPECT_EQ(joint["unit"], "rad");
  const double largest = report["max_position_difference"]["value"].get<double>();
  std::printf("bullet vs mujoco, seed PID to 0.3 rad over 10 s: largest |dq| %.3g rad at t = %.2f s "
              "(bound %.3g, max|v| %.3f rad/s), rms %.3g rad, largest |dv| %.3g rad/s\n",
              largest, joint["max_position_difference_time"].get<double>(), bound, max_speed,
              joint["rms_position_difference"].get<double>(), joint["max_velocity_difference"].get<double>());
  EXPECT_LT(largest, bound);
  EXPECT_EQ(report["within_tolerance"], true);
  // Both ran the scenario: the integral brings joint1 towards 0.3 rad.
  EXPECT_NEAR(joint["final_position"]["bullet"].get<double>(), 0.3, 0.05);
  EXPECT_NEAR(joint["final_position"]["mujoco"].get<double>(), 0.3, 0.05);
  const std::string png = readFile(cli.dir() / "compare.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(BackendCompare, SeedPidToOneRadianThroughTheVelocityLimit) {
  if (!backendBuilt("bullet") || !backendBuilt("mujoco")) GTEST_SKIP() << "needs the bullet and mujoco backends";
  // The seed's own scenario (command 1.0) is not smooth: joint1 reaches its
  // 0.5 rad/s limit within 0.05 s, where the effort saturation cuts the
  // pushing effort whenever the speed is past the limit. The speed then
  // chatters around the limit, each engine switching on its own steps, and
  // stays within one step's velocity change of it: |Δv| ≤ dt·a_max with
  // a_max = (e_max + m g d)/I = (10 + 4.905)/0.35 = 42.6 rad/s² (the 10 N·m
  // effort limit and gravity on link2's 0.35 kg·m² about joint1). Then gravity
  // takes the inverted link past the limit with no effort at all (it reaches
  // about 1.2 rad/s), an unstable fall (growth ≈ 2.5 /s) that amplifies the
  // difference left by the chattering until the PID brakes. So only the
  // velocity has a step-size bound here; the position difference is reported
  // (about 1.8e-3 rad at 1 ms, see docs/comparing_backends.md), and once the
  // closed loop is smooth again it contracts: by 10 s the runs are back within
  // the first-order bound dt·max|q̇| (max|q̇| ≤ 1.3 rad/s).
  constexpr double kDt = 0.001;
  constexpr double kMaxAcceleration = (10.0 + kSeedMgd) / (0.1 + 1.0 * 0.5 * 0.5);
  CliRun cli;
  const std::string launch = (kRobots / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml").string();
  const CliResult result = cli.run("compare '" + launch + "' --backends bullet,mujoco --duration 10 --json --pub " +
                                   kSeedPidCommand + ":=1.0");
  ASSERT_EQ(result.status, 0) << result.err << result.out;
  const json report = json::parse(result.out);
  const json& joint = report["topics"][0]["joints"][0];
  const double position_difference = joint["max_position_difference"].get<double>();
  const double velocity_difference = joint["max_velocity_difference"].get<double>();
  const double final_difference =
      std::abs(joint["final_position"]["bullet"].get<double>() - joint["final_position"]["mujoco"].get<double>());
  std::printf("bullet vs mujoco, seed PID to 1.0 rad over 10 s: largest |dq| %.3g rad at t = %.2f s, "
              "largest |dv| %.3g rad/s (bound %.3g), |dq| at the end %.3g rad\n",
              position_difference, joint["max_position_difference_time"].get<double>(), velocity_difference,
              kDt * kMaxAcceleration, final_difference);
  EXPECT_LT(velocity_difference, kDt * kMaxAcceleration);
  EXPECT_LT(final_difference, kDt * 1.3);
  EXPECT_GT(position_difference, final_difference);
}

TEST(BackendCompare, ToleranceExceededExitsNonZeroAfterTheReport) {
  if (!backendBuilt("bullet")) GTEST_SKIP() << "needs the bullet backend";
  // Mock has no gravity: the raw PD reaches 1.0 there, 1.49 rad on bullet.
  CliRun cli;
  const std::string launch = (kRobots / "one_dof" / "one_dof_raw_pd.launch.yaml").string();
  const CliResult result = cli.run("compare '" + launch +
                                   "' --backends bullet,mock --duration 5 --tolerance 0.01"
                                   " --pub /one_DOF_robot/minimal_joint_controller/pos_cmd:=1.0");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.out.find("servoloop compare one_dof_raw_pd.launch.yaml: bullet vs mock"), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("joint1"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("exceeds --tolerance 0.01"), std::string::npos) << result.out;
  EXPECT_NE(result.err.find("largest position difference"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("exceeds --tolerance 0.01"), std::string::npos) << result.err;
}

TEST(BackendCompare, WithoutToleranceTheComparisonIsInformation) {
  CliRun cli;
  const std::string launch = (kRobots / "one_dof" / "one_dof_raw_pd.launch.yaml").string();
  const CliResult result = cli.run("compare '" + launch +
                                   "' --backends mock,bullet --duration 1 --json"
                                   " --pub /one_DOF_robot/minimal_joint_controller/pos_cmd:=1.0");
  if (!backendBuilt("bullet")) GTEST_SKIP() << "needs the bullet backend";
  ASSERT_EQ(result.status, 0) << result.err;
  const json report = json::parse(result.out);
  EXPECT_GT(report["max_position_difference"]["value"].get<double>(), 0.01);
  EXPECT_TRUE(report["tolerance"].is_null());
  EXPECT_FALSE(report.contains("within_tolerance"));
}

struct BadCompare {
  const char* args;
  const char* expected;  // in the stderr line
};

class BackendCompareErrors : public ::testing::TestWithParam<BadCompare> {};

TEST_P(BackendCompareErrors, ExitNonZeroWithOneLine) {
  CliRun cli;
  std::ofstream(cli.dir() / "no_states.launch.yaml")
      << "world: {backend: mock}\nrobots:\n  - urdf: '" << (kRobots / "one_dof" / "minimal_robot_description.urdf").string()
      << "'\n    model: one_DOF_robot\n    controllers: []\n";
  std::string args = GetParam().args;
  const std::string seed = "'" + (kRobots / "one_dof" / "one_dof_w_jnt_ctl.launch.yaml").string() + "'";
  if (const auto at = args.find("SEED"); at != std::string::npos) args.replace(at, 4, seed);
  const CliResult result = cli.run(args);
  EXPECT_NE(result.status, 0);
  EXPECT_TRUE(result.out.empty()) << result.out;
  // The last stderr line is the error (the runs before it may log).
  const std::string last_line = result.err.substr(result.err.rfind('\n', result.err.size() - 2) + 1);
  EXPECT_NE(last_line.find(GetParam().expected), std::string::npos) << result.err;
}

INSTANTIATE_TEST_SUITE_P(
    Flags, BackendCompareErrors,
    ::testing::Values(
        BadCompare{"compare SEED --backends bullet,warp", "unknown backend 'warp'; available backends: "},
        BadCompare{"compare SEED --backends mock", "expected two different backends"},
        BadCompare{"compare SEED --backends mock,mock", "expected two different backends"},
        BadCompare{"compare SEED --backends mock,mock --duration 0", "--duration"},
        BadCompare{"compare SEED --backends mock,bullet --duration 0.1 --topic /other/joint_states",
                   "--topic /other/joint_states: no robot's namespace contains it (robots: /one_DOF_robot)"},
        BadCompare{"compare SEED --backends mock,bullet --duration 0.1 --topic "
                   "/one_DOF_robot/joint1_position_controller/state",
                   "carries control_msgs/JointControllerState; compare reads sensor_msgs/JointState"},
        BadCompare{"compare no_states.launch.yaml --backends mock,bullet --duration 0.1",
                   "topic '/one_DOF_robot/joint_states': nothing was recorded on backend 'mock'"}));

}  // namespace
