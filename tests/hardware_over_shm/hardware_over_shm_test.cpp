// examples/hardware_over_shm end to end: servoloop_example_drive simulates a
// rotor (J = 0.01 kg·m², b = 0.05 N·m·s/rad) on its own clock, and
// `servoloop launch` of the example's launch file drives it through the
// example/ShmDriveHardware plugin at 1 kHz on the wall clock. The position
// loop settles on its command (no gravity, no load: exactly the command, to
// the encoder's 2π/4096 rad); killing the drive mid-run puts the robot in a
// protective stop while the node keeps serving; a new drive and `control
// recover` take it back.
#include <sys/stat.h>

#include <csignal>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using json = nlohmann::json;

constexpr double kWait_s = 30.0;
const fs::path kConfig = SERVOLOOP_EXAMPLE_CONFIG_DIR;
constexpr double kEncoderStep = 2.0 * M_PI / 4096.0;

class HardwareOverShm : public ::testing::Test {
 protected:
  void SetUp() override {
    // A drive name of this test's own, in the example's launch file.
    drive_name_ = "servoloop_test_drive_" + std::to_string(getpid());
    std::ifstream in(kConfig / "rotor.launch.yaml");
    std::stringstream text;
    text << in.rdbuf();
    std::string launch = text.str();
    const std::string key = "drive: servoloop_example_drive";
    ASSERT_NE(launch.find(key), std::string::npos);
    launch.replace(launch.find(key), key.size(), "drive: " + drive_name_);
    // Beside it, the files it names (relative to its folder).
    for (const std::string file : {"rotor.urdf", "rotor_controllers.yaml"}) {
      fs::copy_file(kConfig / file, scratch() / file);
    }
    std::ofstream(scratch() / "rotor.launch.yaml") << launch;
  }

  void TearDown() override {
    if (node_) {
      node_->signal(SIGINT);
      node_->wait(kWait_s);
    }
    if (drive_) {
      drive_->signal(SIGINT);
      drive_->wait(kWait_s);
    }
    fs::remove(fs::path("/dev/shm") / drive_name_);
  }

  const fs::path& scratch() const { return run_dir_.scratch(); }
  CliResult cli(const std::vector<std::string>& args) { return runCli(args, scratch(), kWait_s); }

  void startDrive() {
    static int starts = 0;
    const fs::path out = scratch() / ("drive" + std::to_string(++starts));
    fs::create_directories(out);
    drive_.emplace(std::vector<std::string>{SERVOLOOP_DRIVE_EXE, "--name", drive_name_, "--unlink"},
                   servoloop::testing::ProcessOptions{out, {}, {}});
    ASSERT_TRUE(drive_->waitForOutput("motor(s) at", kWait_s)) << drive_->currentErr();
  }

  bool waitFor(const std::function<bool()>& done) { return waitUntil(done, kWait_s); }

  std::string state() {
    const CliResult result = cli({"control", "safety", "--json"});
    return result.status == 0 ? json::parse(result.out).value("state", "") : "";
  }

  std::optional<json> jointState() {
    const CliResult echo = cli({"topic", "echo", "-n", "1", "--json", "/shm_rotor/joint_states"});
    if (echo.status != 0) return std::nullopt;
    return json::parse(echo.out);
  }

  // Settled: at the command within one encoder step, and still.
  bool settlesAt(double target) {
    return waitFor([&] {
      const auto js = jointState();
      return js && std::abs(js->at("position")[0].get<double>() - target) <= kEncoderStep &&
             std::abs(js->at("velocity")[0].get<double>()) < 0.01;
    });
  }

  void command(double position) {
    const CliResult pub = cli({"topic", "pub", "/shm_rotor/joint1_position_controller/command", "std_msgs/Float64",
                               std::to_string(position)});
    ASSERT_EQ(pub.status, 0) << pub.err;
  }

  ScopedRunDir run_dir_;
  std::string drive_name_;
  std::optional<servoloop::testing::ChildProcess> drive_;
  std::optional<CliProcess> node_;
};

TEST_F(HardwareOverShm, TheRotorFollowsItsCommandsAndSurvivesItsDriveBeingKilled) {
  // Without a drive the launch fails at once, saying what to start.
  const CliResult no_drive = runCli({"launch", (scratch() / "rotor.launch.yaml").string(), "--plugin-dir",
                                     SERVOLOOP_EXAMPLE_PLUGIN_DIR, "--duration", "1"},
                                    scratch(), kWait_s);
  EXPECT_NE(no_drive.status, 0);
  EXPECT_THAT(no_drive.err, HasSubstr("start the drive process first: servoloop_example_drive --name " + drive_name_));

  startDrive();
  node_.emplace(std::vector<std::string>{"launch", (scratch() / "rotor.launch.yaml").string(), "--plugin-dir",
                                         SERVOLOOP_EXAMPLE_PLUGIN_DIR},
                scratch());
  ASSERT_TRUE(waitFor([&] { return state() == "running"; })) << node_->currentErr();
  command(1.0);
  ASSERT_TRUE(settlesAt(1.0));

  // The drive dies: read() fails within the heartbeat timeout, the position
  // controller is stopped, the node keeps serving.
  drive_->signal(SIGKILL);
  drive_->wait(kWait_s);
  ASSERT_TRUE(waitFor([&] { return state() == "protective_stop"; }));
  const CliResult safety = cli({"control", "safety"});
  EXPECT_THAT(safety.out, HasSubstr("read() returned an error"));
  const CliResult list = cli({"control", "list", "--json"});
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("\"failed\""));
  const CliResult recover_without_drive = cli({"control", "recover"});
  EXPECT_EQ(recover_without_drive.status, 1);
  EXPECT_THAT(recover_without_drive.err, HasSubstr("failed again"));

  // A new drive (its rotor starts at 0 rad) and an explicit recovery.
  startDrive();
  const CliResult recovered = cli({"control", "recover"});
  ASSERT_EQ(recovered.status, 0) << recovered.err;
  EXPECT_EQ(state(), "running");
  command(-0.5);
  ASSERT_TRUE(settlesAt(-0.5));
}

}  // namespace
}  // namespace servoloop::cli::testing
