// Joint trajectory controllers tracking trajectories in simulation, run as
// users run them (`servoloop launch` with a timed trajectory and a recording
// of the controller's state topic), on bullet and mujoco:
//
//  - the desired state is the minimum-jerk quintic the trajectory's one
//    point (at rest, zero acceleration) asks for, evaluated here by hand;
//  - the tracking error stays inside a bound worked out from the gains, the
//    robot and the step: an effort PD without feed-forward carries the load
//    torque τ (inertia × acceleration, viscous damping × velocity, gravity)
//    with an error of about τ/kp while the trajectory is slow next to the
//    closed loop, plus one step of motion, v·dt; the bound is 1.5 times that;
//  - at the end the joints come to rest where gravity balances the PD, the
//    error inside the goal tolerance the YAML gives.
//
// Robots: the seed's one-joint robot (an inverted pendulum on joint1) and the
// six-joint chain (robots/chain: planar, hanging), with effort trajectory
// controllers of their own here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "csv_columns.hpp"
#include "physics_backends.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kRobots = fs::path(SERVOLOOP_SOURCE_DIR) / "robots";
constexpr double kG = 9.81;
constexpr double kDt = 0.001;

// Minimum-jerk position, velocity and acceleration from q0 to q1 over T.
struct Quintic {
  double q0, q1, T;
  double s(double t) const { return std::clamp(t / T, 0.0, 1.0); }
  double position(double t) const {
    const double x = s(t);
    return q0 + (q1 - q0) * x * x * x * (10 - 15 * x + 6 * x * x);
  }
  double maxVelocity() const { return 1.875 * std::abs(q1 - q0) / T; }
  double maxAcceleration() const { return 5.7735 * std::abs(q1 - q0) / (T * T); }
};

struct LaunchRun {
  std::map<std::string, std::vector<double>> state;
  std::string out;
};

// Writes the launch and parameter files into dir and runs `servoloop launch`.
// ns: the robot's namespace (the seed's URDF names its own, /one_DOF_robot).
LaunchRun launch(const fs::path& dir, const std::string& backend, const std::string& ns, const std::string& launch_yaml,
                 const std::string& params_yaml, double duration) {
  std::ofstream(dir / "robot.launch.yaml") << launch_yaml;
  std::ofstream(dir / "controllers.yaml") << params_yaml;
  const auto result = servoloop::testing::runShell(
      std::string("exec '") + SERVOLOOP_CLI_EXE + "' launch robot.launch.yaml --backend " + backend +
          " --duration " + std::to_string(duration) + " --record " + ns + "/arm_controller/state=state.csv",
      {dir, dir, {{"SERVOLOOP_PLUGIN_PATH", std::nullopt}, {"SERVOLOOP_RUN_DIR", dir.string()}}}, 300.0);
  EXPECT_EQ(result.status, 0) << result.err;
  return {servoloop::testing::readCsvColumns(dir / "state.csv"), result.out + result.err};
}

std::string trajectoryPublish(const std::string& ns, const std::vector<std::string>& joints,
                              const std::vector<double>& goal, double T, double at) {
  std::string names, positions, zeros;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    names += (j ? ", " : "") + joints[j];
    positions += (j ? ", " : "") + std::to_string(goal[j]);
    zeros += std::string(j ? ", " : "") + "0";
  }
  return "publish:\n"
         "  - topic: " + ns + "/arm_controller/command\n"
         "    type: trajectory_msgs/JointTrajectory\n"
         "    time: " + std::to_string(at) + "\n"
         "    value: {joint_names: [" + names + "], points: [{positions: [" + positions + "], velocities: [" + zeros +
         "], accelerations: [" + zeros + "], time_from_start: " + std::to_string(T) + "}]}\n";
}

// Checks the desired state against the quintic and the error against bound[j]
// while the trajectory runs; returns the largest error seen per joint.
std::vector<double> checkTracking(const LaunchRun& run, const std::vector<Quintic>& quintics,
                                  const std::vector<double>& bound) {
  const auto& time_from_start = run.state.at("desired.time_from_start");
  std::vector<double> largest(quintics.size(), 0.0);
  std::size_t during = 0;
  for (std::size_t r = 0; r < time_from_start.size(); ++r) {
    const double t = time_from_start[r];
    if (t <= 0.0) continue;
    ++during;
    for (std::size_t j = 0; j < quintics.size(); ++j) {
      const std::string index = "[" + std::to_string(j) + "]";
      EXPECT_NEAR(run.state.at("desired.positions" + index)[r], quintics[j].position(t), 1e-9) << "joint " << j;
      const double error = std::abs(run.state.at("error.positions" + index)[r]);
      largest[j] = std::max(largest[j], error);
      if (t <= quintics[j].T) {
        EXPECT_LT(error, bound[j]) << "joint " << j << " at " << t << " s";
      }
    }
  }
  EXPECT_GT(during, 100u);  // the state was recorded through the trajectory
  return largest;
}

TEST(TrajectoryTracking, SeedRobotFollowsAMinimumJerkMoveWithinItsBound) {
  // joint1: link2 of 1 kg, centre of mass 0.5 m from the axis, iyy 0.1 there:
  // I = 0.1 + 1·0.5² = 0.35 kg·m²; gravity m·g·r·sin q (q = 0 is upright);
  // damping 1 N·m·s/rad; effort limit 10 N·m, velocity limit 0.5 rad/s. The
  // move 0 → 1 rad in 4 s keeps below the velocity limit (0.47 rad/s).
  const double kp = 200.0, I = 0.35, b = 1.0, m_g_r = 1.0 * kG * 0.5;
  const Quintic move{0.0, 1.0, 4.0};
  const double load = I * move.maxAcceleration() + b * move.maxVelocity() + m_g_r * std::sin(1.0);
  const double bound = 1.5 * (load / kp + move.maxVelocity() * kDt);
  const std::string urdf = (kRobots / "one_dof" / "minimal_robot_description_w_jnt_ctl.urdf").string();
  for (const std::string& backend : servoloop::testing::physicsBackends()) {
    SCOPED_TRACE(backend);
    servoloop::testing::TempDir dir("servoloop-jtc-seed");
    const LaunchRun run = launch(dir.path(), backend, "/one_DOF_robot",
                           "world: {time_step: 0.001, gravity: [0, 0, -9.81]}\n"
                           "robots:\n  - urdf: " + urdf + "\n"
                           "    params: [controllers.yaml]\n    controllers: [arm_controller]\n" +
                               trajectoryPublish("/one_DOF_robot", {"joint1"}, {1.0}, move.T, 0.5),
                           "one_DOF_robot:\n  arm_controller:\n    type: effort_controllers/JointTrajectoryController\n"
                           "    joints: [joint1]\n    gains: {joint1: {p: 200, d: 20}}\n"
                           "    state_publish_rate: 200\n",
                           6.0);
    const std::vector<double> largest = checkTracking(run, {move}, {bound});
    EXPECT_GT(largest[0], 0.2 * bound);  // the bound is not loose by orders of magnitude
    // At rest at the end the PD holds gravity, which tips the upright link
    // further along +q: the joint stops past its goal, e = −m·g·r·sin(q)/kp
    // (q ≈ 1; the 2% change of sin q over e is inside the tolerance).
    const double final_error = run.state.at("error.positions[0]").back();
    EXPECT_NEAR(final_error, -m_g_r * std::sin(1.0) / kp, 0.1 * m_g_r / kp);
  }
}

// A trajectory published by the launch file at t = 0 starts at t = 0, in
// every run: its state recordings are identical, stamp for stamp (the
// publication is delivered to the controller before the loop goes on).
TEST(TrajectoryTracking, ATimedTrajectoryStartsAtItsTimeInEveryRun) {
  const std::string urdf = (kRobots / "one_dof" / "minimal_robot_description_w_jnt_ctl.urdf").string();
  const std::string launch_yaml = "world: {time_step: 0.001, gravity: [0, 0, -9.81]}\n"
                                  "robots:\n  - urdf: " + urdf + "\n"
                                  "    params: [controllers.yaml]\n    controllers: [arm_controller]\n" +
                                  trajectoryPublish("/one_DOF_robot", {"joint1"}, {0.5}, 0.2, 0.0);
  const std::string params = "one_DOF_robot:\n  arm_controller:\n    type: effort_controllers/JointTrajectoryController\n"
                             "    joints: [joint1]\n    gains: {joint1: {p: 200, d: 20}}\n"
                             "    state_publish_rate: 1000\n";
  const std::string backend = servoloop::testing::physicsBackends().front();
  std::vector<std::vector<double>> starts;
  for (int run = 0; run < 5; ++run) {
    servoloop::testing::TempDir dir("servoloop-jtc-start");
    const LaunchRun result = launch(dir.path(), backend, "/one_DOF_robot", launch_yaml, params, 0.03);
    const auto& time = result.state.at("time");
    const auto& from_start = result.state.at("desired.time_from_start");
    ASSERT_FALSE(time.empty());
    // The trajectory's start: the state's time minus its time from start, once it runs.
    std::vector<double> start;
    for (std::size_t r = 0; r < time.size(); ++r) {
      if (from_start[r] > 0.0) start.push_back(time[r] - from_start[r]);
    }
    ASSERT_FALSE(start.empty());
    for (const double t : start) EXPECT_NEAR(t, 0.0, 1e-9) << "run " << run;
    starts.push_back(start);
  }
  for (const auto& start : starts) EXPECT_EQ(start.size(), starts.front().size());
}

// The chain (robots/chain/chain.urdf): six 0.5 kg plates, 0.25 m long, centre
// of mass 0.125 m below each joint, iyy 0.01 kg·m² there, damping 0.5, planar
// about y. Positive q swings the chain towards −x.
struct ChainModel {
  static constexpr int kLinks = 6;
  static constexpr double kMass = 0.5, kLength = 0.25, kCom = 0.125, kIyy = 0.01, kDamping = 0.5;

  // Gravity torque each joint must supply at q (statics of the planar chain).
  static std::vector<double> gravity(const std::vector<double>& q) {
    std::vector<double> joint_x(kLinks), com_x(kLinks);
    double x = 0.0, phi = 0.0;
    for (int k = 0; k < kLinks; ++k) {
      phi += q[k];
      joint_x[k] = x;
      com_x[k] = x - kCom * std::sin(phi);
      x -= kLength * std::sin(phi);
    }
    std::vector<double> tau(kLinks, 0.0);
    for (int j = 0; j < kLinks; ++j) {
      for (int k = j; k < kLinks; ++k) tau[j] += kMass * kG * (com_x[k] - joint_x[j]);
    }
    return tau;
  }
  // The largest inertia about joint j the links below it can present (chain straight).
  static double maxInertia(int j) {
    double inertia = 0.0;
    for (int k = j; k < kLinks; ++k) {
      const double d = kLength * (k - j) + kCom;
      inertia += kIyy + kMass * d * d;
    }
    return inertia;
  }
};

TEST(TrajectoryTracking, SixJointChainFollowsAMinimumJerkMoveWithinItsBound) {
  const std::vector<std::string> joints = {"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6"};
  const std::vector<double> kp = {150, 120, 90, 60, 40, 20};  // the chain's own gains (control_config)
  const std::vector<double> kd = {6, 5, 4, 3, 2, 1};
  const std::vector<double> goal = {0.3, -0.2, 0.2, -0.15, 0.1, -0.1};
  const double T = 3.0;
  std::vector<Quintic> moves;
  for (double g : goal) moves.push_back({0.0, g, T});
  // Bound per joint: gravity along the path (sampled), inertia coupling
  // |M_jk| ≤ sqrt(M_jj M_kk) times each joint's peak acceleration, damping,
  // one step of motion.
  std::vector<double> bound(6);
  for (int j = 0; j < 6; ++j) {
    double gravity_peak = 0.0;
    for (int n = 0; n <= 100; ++n) {
      std::vector<double> q(6);
      for (int k = 0; k < 6; ++k) q[k] = moves[k].position(T * n / 100.0);
      gravity_peak = std::max(gravity_peak, std::abs(ChainModel::gravity(q)[j]));
    }
    double inertial = 0.0;
    for (int k = 0; k < 6; ++k) {
      inertial += std::sqrt(ChainModel::maxInertia(j) * ChainModel::maxInertia(k)) * moves[k].maxAcceleration();
    }
    const double load = gravity_peak + inertial + ChainModel::kDamping * moves[j].maxVelocity();
    bound[j] = 1.5 * (load / kp[j] + moves[j].maxVelocity() * kDt);
  }
  std::string gains, constraints;
  for (int j = 0; j < 6; ++j) {
    gains += "      " + joints[j] + ": {p: " + std::to_string(kp[j]) + ", d: " + std::to_string(kd[j]) + "}\n";
    constraints += "      " + joints[j] + ": {goal: " + std::to_string(bound[j]) + "}\n";
  }
  const std::string urdf = (kRobots / "chain" / "chain.urdf").string();
  for (const std::string& backend : servoloop::testing::physicsBackends()) {
    SCOPED_TRACE(backend);
    servoloop::testing::TempDir dir("servoloop-jtc-chain");
    const LaunchRun run = launch(dir.path(), backend, "/robot",
                           "world: {time_step: 0.001, gravity: [0, 0, -9.81]}\n"
                           "robots:\n  - urdf: " + urdf + "\n    namespace: /robot\n"
                           "    params: [controllers.yaml]\n    controllers: [arm_controller]\n" +
                               trajectoryPublish("/robot", joints, goal, T, 0.5),
                           "robot:\n  arm_controller:\n    type: effort_controllers/JointTrajectoryController\n"
                           "    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]\n"
                           "    gains:\n" + gains + "    constraints:\n" + constraints +
                               "    state_publish_rate: 100\n",
                           4.5);
    const std::vector<double> largest = checkTracking(run, moves, bound);
    for (int j = 0; j < 6; ++j) {
      EXPECT_LT(std::abs(run.state.at("error.positions[" + std::to_string(j) + "]").back()), bound[j]) << j;
      std::cout << backend << " " << joints[j] << ": largest error " << largest[j] << " rad, bound " << bound[j]
                << " rad\n";
    }
  }
}

}  // namespace
