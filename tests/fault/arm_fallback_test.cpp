// A gravity-loaded arm whose controller faults holds instead of dropping when
// the controller names a fallback (`fallback_controllers`), run as users run
// it: `servoloop launch` of the two-joint arm on bullet with a controller
// that holds the arm raised and faults at t = 2 s (a test plugin), once with
// and once without a holding fallback.
//
// By hand, for the arm of robots/two_joint_arm (upper arm 1.5 kg with its
// centre of mass 0.25 m out, forearm 1.0 kg at 0.2 m past the 0.5 m upper
// arm): the fallback starts holding where the arm is at the fault, so gravity
// then sags each joint by about τ_g/kp more (τ_g the gravity torque at the
// pose). Without the fallback the commands go to zero and the arm falls.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "csv_columns.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
constexpr double kG = 9.81;

// Runs the arm with the faulting controller, with or without the fallback;
// returns the recorded joint states.
std::map<std::string, std::vector<double>> run(bool with_fallback) {
  servoloop::testing::TempDir dir("servoloop-arm-fallback");
  const fs::path arm = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "two_joint_arm" / "two_joint_arm.urdf";
  std::ofstream(dir.path() / "controllers.yaml")
      << "arm:\n"
         "  joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 50}\n"
         "  arm_controller:\n"
         "    type: servoloop_test/FaultingHoldController\n"
         "    joints: [shoulder, elbow]\n"
         "    setpoints: [-0.6, 0.5]\n"
         "    p: 200\n"
         "    d: 10\n"
         "    fault_after: 2.0\n"
      << (with_fallback ? "    fallback_controllers: [arm_hold_controller]\n" : "")
      << "  arm_hold_controller:\n"
         "    type: effort_controllers/JointGroupPositionController\n"
         "    joints: [shoulder, elbow]\n"
         "    shoulder: {pid: {p: 200.0, d: 10.0}}\n"
         "    elbow: {pid: {p: 100.0, d: 5.0}}\n";
  std::ofstream(dir.path() / "arm.launch.yaml")
      << "world: {backend: bullet, time_step: 0.001, gravity: [0, 0, -9.81], ground_plane: false}\n"
         "robots:\n"
         "  - urdf: " << arm.string() << "\n"
         "    namespace: /arm\n"
         "    params: [controllers.yaml]\n"
         "    stopped_controllers: [arm_hold_controller]\n"
         "    controllers: [joint_state_controller, arm_controller]\n";
  const auto result = servoloop::testing::runShell(
      std::string("exec '") + SERVOLOOP_CLI_EXE +
          "' launch arm.launch.yaml --duration 4 --record /arm/joint_states=joint_states.csv",
      {dir.path(), dir.path(), {{"SERVOLOOP_PLUGIN_PATH", SERVOLOOP_FAULT_PLUGIN_DIR}}}, 120.0);
  EXPECT_NE(result.err.find("'arm_controller' (type 'servoloop_test/FaultingHoldController') was stopped and marked failed"),
            std::string::npos)
      << "the fault is reported: " << result.err;
  // The node shuts down cleanly: the fallback is unloaded after the controller naming it.
  EXPECT_EQ(result.err.find("[E] unload"), std::string::npos) << result.err;
  return servoloop::testing::readCsvColumns(dir.path() / "joint_states.csv");
}

// The index of the first row at or after time t.
std::size_t rowAt(const std::vector<double>& time, double t) {
  std::size_t i = 0;
  while (i < time.size() && time[i] < t - 1e-9) ++i;
  return i;
}

TEST(ArmFallback, AGravityLoadedArmHoldsWhenItsControllerFaults) {
  // Gravity torques at the raised pose (q1 = −0.6, q2 = 0.5; joints about y,
  // links along x): each joint carries the links outboard of it.
  const double q1 = -0.6, q2 = 0.5;
  const double shoulder_torque =
      kG * (1.5 * 0.25 * std::cos(q1) + 1.0 * (0.5 * std::cos(q1) + 0.2 * std::cos(q1 + q2)));
  const double elbow_torque = kG * 1.0 * 0.2 * std::cos(q1 + q2);
  const double shoulder_sag = shoulder_torque / 200.0;  // the fallback's kp
  const double elbow_sag = elbow_torque / 100.0;

  const auto held = run(true);
  ASSERT_FALSE(held.empty());
  const auto& t = held.at("time");
  const std::size_t fault = rowAt(t, 2.0), end = t.size() - 1;
  ASSERT_LT(fault, end);
  const double shoulder_drift = held.at("shoulder.position")[end] - held.at("shoulder.position")[fault];
  const double elbow_drift = held.at("elbow.position")[end] - held.at("elbow.position")[fault];
  // Settled 2 s later one more sag away (ζ ≈ 0.45 at the shoulder: settled well
  // before); the fault's step in effort leaves nothing else behind.
  EXPECT_NEAR(std::abs(shoulder_drift), shoulder_sag, 0.25 * shoulder_sag);
  EXPECT_NEAR(std::abs(elbow_drift), elbow_sag, 0.5 * elbow_sag);
  double largest = 0.0;
  for (std::size_t i = fault; i <= end; ++i) {
    largest = std::max(largest, std::abs(held.at("shoulder.position")[i] - held.at("shoulder.position")[fault]));
  }
  EXPECT_LT(largest, 2.0 * shoulder_sag);  // no drop on the way either

  const auto dropped = run(false);
  ASSERT_FALSE(dropped.empty());
  double fallen = 0.0;
  const std::size_t dropped_fault = rowAt(dropped.at("time"), 2.0);
  for (std::size_t i = dropped_fault; i < dropped.at("time").size(); ++i) {
    fallen = std::max(fallen, std::abs(dropped.at("shoulder.position")[i] -
                                       dropped.at("shoulder.position")[dropped_fault]));
  }
  EXPECT_GT(fallen, 0.5);  // without the fallback the arm swings down
}

}  // namespace
