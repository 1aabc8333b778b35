// `servoloop check-urdf` on the seed robots and on broken descriptions.
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_client_support.hpp"

namespace servoloop::cli::testing {
namespace {

using ::testing::HasSubstr;
using nlohmann::json;

const std::string kSeed = std::string(SERVOLOOP_SEED_DIR) + "/";

class CheckUrdfTest : public ::testing::Test {
 protected:
  ScopedRunDir run_dir_;
};

TEST_F(CheckUrdfTest, SeedWithTransmissionText) {
  const std::string urdf = kSeed + "minimal_robot_description_w_jnt_ctl.urdf";
  const CliResult result = runCli({"check-urdf", urdf}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("robot name is: one_DOF_robot\n"
                                    "---------- Successfully Parsed XML ---------------\n"
                                    "root Link: world has 1 child(ren)\n"
                                    "    child(1):  link1\n"
                                    "        child(1):  link2\n"));
  EXPECT_THAT(result.out, HasSubstr("  joint1 (revolute): link1 -> link2\n"
                                    "      axis: [0.0, 1.0, 0.0]\n"
                                    "      limits: position [0.0, 2.0], velocity 0.5, effort 10.0\n"
                                    "      dynamics: damping 1.0, friction 0.0\n"
                                    "      soft limits: none\n"));
  EXPECT_THAT(result.out, HasSubstr("  glue_robot_to_world (fixed): world -> link1\n"));
  EXPECT_THAT(result.out,
              HasSubstr("  tran1 (transmission_interface/SimpleTransmission)\n"
                        "      joint joint1: [EffortJointInterface], reduction 1.0, offset 0.0\n"
                        "      actuator motor1: [EffortJointInterface], reduction 1.0\n"));
  EXPECT_THAT(result.out, HasSubstr("  joint1: JointStateInterface, EffortJointInterface\n"
                                    "  actuators: motor1\n"));
  EXPECT_THAT(result.out, ::testing::Not(HasSubstr("implicit")));
}

TEST_F(CheckUrdfTest, SeedWithoutTransmissionNotesTheImplicitOne) {
  const std::string urdf = kSeed + "minimal_robot_description.urdf";
  CliResult result = runCli({"check-urdf", urdf}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  joint1 (continuous): link1 -> link2\n"
                                    "      axis: [0.0, 1.0, 0.0]\n"
                                    "      limits: position unlimited (wraps), velocity -, effort -\n"));
  EXPECT_THAT(result.out, HasSubstr("transmissions: none\n"));
  EXPECT_THAT(result.out,
              HasSubstr("  joint1: JointStateInterface, EffortJointInterface, VelocityJointInterface, "
                        "PositionJointInterface  (no <transmission>: "
                        "implicit SimpleTransmission, reduction 1, actuator joint1_motor)\n"));

  result = runCli({"check-urdf", "--json", urdf}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto report = json::parse(result.out);
  EXPECT_EQ(report["robot"], "one_DOF_robot");
  EXPECT_EQ(report["root_link"], "world");
  EXPECT_EQ(report["tree"]["children"][0]["children"][0]["link"], "link2");
  EXPECT_EQ(report["transmissions"], json::array());
  const auto joint = report["joints"][1];
  EXPECT_EQ(joint["name"], "joint1");
  EXPECT_EQ(joint["type"], "continuous");
  // No <limit>: only the wrap-around a continuous joint always has.
  EXPECT_EQ(joint["limits"], json({{"wraps", true}}));
  const auto hardware_joint = report["hardware"]["joints"][0];
  EXPECT_EQ(hardware_joint["name"], "joint1");
  EXPECT_EQ(hardware_joint["interfaces"], json({"JointStateInterface", "EffortJointInterface", "VelocityJointInterface",
                                                     "PositionJointInterface"}));
  EXPECT_EQ(hardware_joint["implicit_transmission"], true);
}

TEST_F(CheckUrdfTest, JsonOfTheSeedWithLimits) {
  const std::string urdf = kSeed + "minimal_robot_description_w_jnt_ctl.urdf";
  const CliResult result = runCli({"check-urdf", urdf, "--json"}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  const auto report = json::parse(result.out);
  const auto joint = report["joints"][1];
  EXPECT_EQ(joint["axis"], json({0.0, 1.0, 0.0}));
  EXPECT_EQ(joint["limits"], json({{"lower", 0.0}, {"upper", 2.0}, {"velocity", 0.5}, {"effort", 10.0}}));
  EXPECT_EQ(joint["dynamics"]["damping"], 1.0);
  const auto transmission = report["transmissions"][0];
  EXPECT_EQ(transmission["name"], "tran1");
  EXPECT_EQ(transmission["actuators"][0]["name"], "motor1");
  EXPECT_EQ(report["hardware"]["joints"][0]["implicit_transmission"], false);
}

TEST_F(CheckUrdfTest, SoftLimitsAreShown) {
  const auto urdf = run_dir_.scratch() / "soft.urdf";
  std::ofstream(urdf) << R"(<robot name="soft">
  <link name="base"/>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="arm"/><axis xyz="1 0 0"/>
    <limit lower="-0.5" upper="0.5" effort="100" velocity="2"/>
    <safety_controller soft_lower_limit="-0.4" soft_upper_limit="0.4" k_position="10" k_velocity="5"/>
  </joint>
</robot>)";
  const CliResult result = runCli({"check-urdf", urdf.string()}, run_dir_.scratch());
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("      limits: position [-0.5, 0.5], velocity 2.0, effort 100.0\n"
                                    "      dynamics: none\n"
                                    "      soft limits: [-0.4, 0.4], k_position 10.0, k_velocity 5.0\n"));
}

TEST_F(CheckUrdfTest, BrokenUrdfFailsWithTheValidationMessage) {
  const auto urdf = run_dir_.scratch() / "broken.urdf";
  std::ofstream(urdf) << R"(<robot name="broken">
  <link name="base"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="ghost"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>)";
  const CliResult result = runCli({"check-urdf", urdf.string()}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr(urdf.string()));
  EXPECT_THAT(result.err, HasSubstr("ghost"));
  EXPECT_TRUE(result.out.empty()) << result.out;
}

TEST_F(CheckUrdfTest, BrokenTransmissionFailsNamingIt) {
  const auto urdf = run_dir_.scratch() / "bad_transmission.urdf";
  std::ifstream seed(kSeed + "minimal_robot_description_w_jnt_ctl.urdf");
  std::string text((std::istreambuf_iterator<char>(seed)), std::istreambuf_iterator<char>());
  const std::string reduction = "<mechanicalReduction>1</mechanicalReduction>";
  text.replace(text.find(reduction), reduction.size(), "<mechanicalReduction>0</mechanicalReduction>");
  std::ofstream(urdf) << text;
  const CliResult result = runCli({"check-urdf", urdf.string()}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("tran1"));
  EXPECT_THAT(result.err, HasSubstr("motor1"));
}

// Without <mechanicalReduction> the actuator drives its joint directly, as
// gazebo_ros_control takes it: a note, not an error.
TEST_F(CheckUrdfTest, TransmissionWithoutReductionIsADirectDriveWithANote) {
  const auto urdf = run_dir_.scratch() / "direct_drive.urdf";
  std::ifstream seed(kSeed + "minimal_robot_description_w_jnt_ctl.urdf");
  std::string text((std::istreambuf_iterator<char>(seed)), std::istreambuf_iterator<char>());
  const std::string reduction = "<mechanicalReduction>1</mechanicalReduction>";
  text.erase(text.find(reduction), reduction.size());
  std::ofstream(urdf) << text;
  const CliResult result = runCli({"check-urdf", urdf.string()}, run_dir_.scratch());
  EXPECT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.err, HasSubstr("actuator motor1 without <mechanicalReduction> is taken as a direct drive "
                                    "(reduction 1)"));
}

TEST_F(CheckUrdfTest, MissingFile) {
  const CliResult result = runCli({"check-urdf", "/no/such/robot.urdf"}, run_dir_.scratch());
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("/no/such/robot.urdf"));
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
}

}  // namespace
}  // namespace servoloop::cli::testing
