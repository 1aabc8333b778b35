// Launch file parsing: the seed's launch files, defaults, the --pub/--record
// flags, and one test per error (each message names the file, line, key, fix).
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "servoloop/node/launch_file.hpp"
#include "servoloop/core/errors.hpp"

namespace {

namespace fs = std::filesystem;
using namespace servoloop::node;

const fs::path kOneDof = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";

LaunchFile parse(const std::string& yaml) { return parseLaunchFile(yaml, "test.launch.yaml", kOneDof); }

// The ConfigError text parse(yaml) throws; fails the test if it does not throw.
std::string errorOf(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const servoloop::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for:\n" << yaml;
  return "";
}

std::string flagErrorOf(std::string_view flag, bool record = false) {
  try {
    if (record) {
      parseRecordFlag(flag);
    } else {
      parsePubFlag(flag);
    }
  } catch (const servoloop::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error for flag " << flag;
  return "";
}

TEST(LaunchFile, SeedLaunchFileWithJointController) {
  const LaunchFile launch = loadLaunchFile(kOneDof / "one_dof_w_jnt_ctl.launch.yaml");
  EXPECT_EQ(launch.source, fs::absolute(kOneDof / "one_dof_w_jnt_ctl.launch.yaml").lexically_normal());
  EXPECT_EQ(launch.world.backend, "bullet");
  EXPECT_DOUBLE_EQ(launch.world.time_step_s, 0.001);
  EXPECT_DOUBLE_EQ(launch.world.gravity[2], -9.81);
  EXPECT_FALSE(launch.world.real_time_factor.has_value());
  EXPECT_DOUBLE_EQ(launch.controller_manager.update_rate_hz, 1000.0);
  ASSERT_EQ(launch.robots.size(), 1u);
  const RobotSpec& robot = launch.robots[0];
  EXPECT_EQ(robot.urdf, (kOneDof / "minimal_robot_description_w_jnt_ctl.urdf").lexically_normal());
  ASSERT_EQ(robot.params.size(), 1u);
  EXPECT_EQ(robot.params[0].file, (kOneDof / "control_config" / "one_dof_ctl_params.yaml").lexically_normal());
  EXPECT_EQ(robot.params[0].ns, "/");
  EXPECT_EQ(robot.controllers, (std::vector<std::string>{"joint_state_controller", "joint1_position_controller"}));
  EXPECT_TRUE(robot.stopped_controllers.empty());
  EXPECT_TRUE(robot.robot_namespace.empty());  // the URDF gives it
}

TEST(LaunchFile, SeedLaunchFileWithRawPd) {
  const LaunchFile launch = loadLaunchFile(kOneDof / "one_dof_raw_pd.launch.yaml");
  ASSERT_EQ(launch.robots.size(), 1u);
  EXPECT_EQ(launch.robots[0].robot_namespace, "/one_DOF_robot");
  EXPECT_EQ(launch.robots[0].urdf.filename(), "minimal_robot_description.urdf");
  EXPECT_EQ(launch.robots[0].controllers,
            (std::vector<std::string>{"joint_state_controller", "minimal_joint_controller"}));
}

TEST(LaunchFile, EmptyFileGivesDefaults) {
  const LaunchFile launch = parse("");
  EXPECT_EQ(launch.world.backend, "bullet");
  EXPECT_DOUBLE_EQ(launch.world.time_step_s, 0.001);
  EXPECT_DOUBLE_EQ(launch.controller_manager.update_rate_hz, 0.0);
  EXPECT_TRUE(launch.robots.empty());
  EXPECT_TRUE(launch.plot.empty());
}

TEST(LaunchFile, EverySection) {
  const LaunchFile launch = parse(R"(
world: {backend: mock, time_step: 0.002, gravity: [0, 0, -1.62], ground_plane: true, real_time_factor: 0}
controller_manager: {update_rate: 250}
robots:
  - urdf: minimal_robot_description.urdf
    model: moon_robot
    namespace: moon
    params: control_config/one_dof_ctl_params.yaml
    controllers: joint_state_controller
    stopped_controllers: [joint1_position_controller]
publish:
  - {topic: /moon/joint1_position_controller/command, value: 0.5, time: 1.5}
  - {topic: /moon/group/command, value: [1, 2.5]}
record:
  - {topic: moon/joint_states, file: out/js.csv}
plot: out/plot.png
)");
  EXPECT_EQ(launch.world.backend, "mock");
  EXPECT_DOUBLE_EQ(launch.world.time_step_s, 0.002);
  EXPECT_DOUBLE_EQ(launch.world.gravity[2], -1.62);
  EXPECT_TRUE(launch.world.ground_plane);
  EXPECT_EQ(launch.world.real_time_factor, 0.0);
  EXPECT_DOUBLE_EQ(launch.controller_manager.update_rate_hz, 250.0);
  ASSERT_EQ(launch.robots.size(), 1u);
  EXPECT_EQ(launch.robots[0].model, "moon_robot");
  EXPECT_EQ(launch.robots[0].robot_namespace, "/moon");
  EXPECT_EQ(launch.robots[0].params.size(), 1u);
  EXPECT_EQ(launch.robots[0].controllers, std::vector<std::string>{"joint_state_controller"});
  EXPECT_EQ(launch.robots[0].stopped_controllers, std::vector<std::string>{"joint1_position_controller"});
  ASSERT_EQ(launch.publish.size(), 2u);
  EXPECT_EQ(launch.publish[0].type, "std_msgs/Float64");
  EXPECT_DOUBLE_EQ(launch.publish[0].time_s, 1.5);
  EXPECT_DOUBLE_EQ(launch.publish[0].message.get<double>(), 0.5);
  EXPECT_EQ(launch.publish[1].type, "std_msgs/Float64MultiArray");
  EXPECT_DOUBLE_EQ(launch.publish[1].time_s, 0.0);
  ASSERT_EQ(launch.record.size(), 1u);
  EXPECT_EQ(launch.record[0].topic, "/moon/joint_states");
  EXPECT_EQ(launch.record[0].file, kOneDof / "out" / "js.csv");
  EXPECT_EQ(launch.plot, kOneDof / "out" / "plot.png");
}

struct ErrorCase {
  const char* name;
  const char* yaml;
  std::vector<const char*> expected;  // substrings of the message
};

class LaunchFileError : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(LaunchFileError, NamesFileLineKeyAndFix) {
  const std::string message = errorOf(GetParam().yaml);
  EXPECT_NE(message.find("test.launch.yaml"), std::string::npos) << message;
  for (const char* part : GetParam().expected) EXPECT_NE(message.find(part), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    AllErrors, LaunchFileError,
    ::testing::Values(
        ErrorCase{"NotYaml", "world: [1, 2", {"not valid YAML"}},
        ErrorCase{"TopLevelNotMap", "- 1\n- 2", {"expected a map"}},
        ErrorCase{"UnknownTopKey", "robot: []", {":1:1:", "unknown key 'robot'", "robots", "check the spelling"}},
        ErrorCase{"UnknownWorldKey", "world:\n  timestep: 0.001", {":2:3:", "world.timestep", "time_step"}},
        ErrorCase{"WorldNotMap", "world: bullet", {"world", "expected a map"}},
        ErrorCase{"TimeStepZero", "world: {time_step: 0}", {"world.time_step", "expected a time step from 1e-06 to 1 s"}},
        ErrorCase{"TimeStepTiny", "world: {time_step: 1e-12}", {"world.time_step", "from 1e-06 to 1 s", "'1e-12'"}},
        ErrorCase{"TimeStepHuge", "world: {time_step: 1e300}", {"world.time_step", "from 1e-06 to 1 s", "'1e300'"}},
        ErrorCase{"UpdateRateNan", "controller_manager: {update_rate: .nan}", {"controller_manager.update_rate", "finite"}},
        ErrorCase{"TimeStepText", "world: {time_step: fast}", {"world.time_step", "expected a number", "'fast'"}},
        ErrorCase{"GravityShort", "world: {gravity: [0, -9.81]}", {"world.gravity", "3 numbers"}},
        ErrorCase{"GravityText", "world: {gravity: [0, 0, down]}", {"world.gravity[2]", "expected a number"}},
        ErrorCase{"GroundPlaneNotBool", "world: {ground_plane: 2}", {"world.ground_plane", "true or false"}},
        ErrorCase{"BackendEmpty", "world: {backend: ''}", {"world.backend", "non-empty string"}},
        ErrorCase{"RtfNegative", "world: {real_time_factor: -1}", {"world.real_time_factor", ">= 0"}},
        ErrorCase{"DuplicateKey", "world: {backend: mock}\nrobots: []\nworld: {backend: bullet}",
                  {":3:1:", "key 'world' appears twice in one map (first at line 1)"}},
        // Found by fuzzing: a string that is not UTF-8 ended the launch with a raw
        // library exception instead of the publication's error.
        ErrorCase{"NotUtf8Value", "publish: [{topic: /a/command, value: \"\xAE\"}]",
                  {"publish[0].value: std_msgs/Float64: expected an object with fields data, got string"}},
        ErrorCase{"AliasBomb",
                  "a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
                  "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
                  "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]\n"
                  "publish: [{topic: /x, value: [*f, *f]}]",
                  {"more than 1000000 values once its aliases"}},
        ErrorCase{"UpdateRateZero", "controller_manager: {update_rate: 0}", {"controller_manager.update_rate", "> 0 Hz"}},
        ErrorCase{"UnknownManagerKey", "controller_manager: {rate: 100}", {"controller_manager.rate", "update_rate"}},
        ErrorCase{"RobotsNotList", "robots: {urdf: a.urdf}", {"robots", "expected a list"}},
        ErrorCase{"RobotNoUrdf", "robots:\n  - model: r", {"robots[0]", "missing 'urdf'"}},
        ErrorCase{"RobotUrdfMissing", "robots:\n  - urdf: nothere.urdf",
                  {":2:11:", "robots[0].urdf", "nothere.urdf", "does not exist", "relative to the launch file"}},
        ErrorCase{"RobotUnknownKey", "robots:\n  - {urdf: minimal_robot_description.urdf, controller: [a]}",
                  {"robots[0].controller", "controllers"}},
        ErrorCase{"RobotParamsMissing", "robots:\n  - {urdf: minimal_robot_description.urdf, params: [x.yaml]}",
                  {"robots[0].params[0]", "parameter file 'x.yaml' does not exist"}},
        ErrorCase{"RobotControllersNotList",
                  "robots:\n  - {urdf: minimal_robot_description.urdf, controllers: {a: 1}}",
                  {"robots[0].controllers", "list of names"}},
        ErrorCase{"RobotBadNamespace", "robots:\n  - {urdf: minimal_robot_description.urdf, namespace: '9lives'}",
                  {"robots[0].namespace"}},
        ErrorCase{"RobotParamsNoFile",
                  "robots:\n  - {urdf: minimal_robot_description.urdf, params: [{ns: /a}]}",
                  {"robots[0].params[0]", "missing 'file'"}},
        ErrorCase{"RobotParamsUnknownKey",
                  "robots:\n  - {urdf: minimal_robot_description.urdf, params: [{file: x.yaml, namespace: /a}]}",
                  {"robots[0].params[0].namespace", "ns"}},
        ErrorCase{"RobotPoseTwoNumbers", "robots:\n  - {urdf: minimal_robot_description.urdf, pose: [1, 2]}",
                  {"robots[0].pose", "[x, y, z, roll, pitch, yaw]"}},
        ErrorCase{"RobotPoseNotNumber", "robots:\n  - {urdf: minimal_robot_description.urdf, pose: [1, 2, up]}",
                  {"robots[0].pose[2]"}},
        ErrorCase{"RobotFixedBaseNotBool", "robots:\n  - {urdf: minimal_robot_description.urdf, fixed_base: yes please}",
                  {"robots[0].fixed_base"}},
        ErrorCase{"PublishNoTopic", "publish:\n  - {value: 1.0}", {"publish[0]", "missing 'topic'"}},
        ErrorCase{"PublishNoValue", "publish:\n  - {topic: /a/command}", {"publish[0]", "missing 'value'"}},
        ErrorCase{"PublishBadTopic", "publish:\n  - {topic: '/a b', value: 1}", {"publish[0].topic"}},
        ErrorCase{"PublishUnknownType", "publish:\n  - {topic: /a, type: std_msgs/String, value: hi}",
                  {"publish[0].value", "unknown message type 'std_msgs/String'", "std_msgs/Float64"}},
        ErrorCase{"PublishValueNotNumber", "publish:\n  - {topic: /a, value: high}",
                  {"publish[0].value", "std_msgs/Float64", "data"}},
        ErrorCase{"PublishNegativeTime", "publish:\n  - {topic: /a, value: 1, time: -2}",
                  {"publish[0].time", ">= 0 s of simulated time"}},
        ErrorCase{"RecordNoFile", "record:\n  - {topic: /a/joint_states}", {"record[0]", "missing 'file'"}},
        ErrorCase{"RecordUnknownKey", "record:\n  - {topic: /a, file: a.csv, rate: 10}", {"record[0].rate"}},
        ErrorCase{"PlotNotString", "plot: [a.png]", {"plot", "non-empty string"}}),
    [](const ::testing::TestParamInfo<ErrorCase>& info) { return std::string(info.param.name); });

// A parameter file with a namespace (roslaunch's <rosparam file ns>), the
// root namespace, and the base, pose and self-collision keys.
TEST(LaunchFile, RobotParametersNamespaceBaseAndPose) {
  const LaunchFile launch = parse(R"(
robots:
  - urdf: minimal_robot_description.urdf
    namespace: /
    params: [control_config/one_dof_ctl_params.yaml, {file: control_config/minimal_joint_controller.yaml, ns: arm}]
    fixed_base: true
    self_collide: true
    pose: [1, 2, 3, 0.1, 0.2, 0.3]
  - urdf: minimal_robot_description.urdf
    params: {file: control_config/one_dof_ctl_params.yaml, ns: /a/b}
    pose: [0, 0, 0.5]
)");
  ASSERT_EQ(launch.robots.size(), 2u);
  const RobotSpec& first = launch.robots[0];
  EXPECT_EQ(first.robot_namespace, "/");
  ASSERT_EQ(first.params.size(), 2u);
  EXPECT_EQ(first.params[0].ns, "/");
  EXPECT_EQ(first.params[1].file, (kOneDof / "control_config" / "minimal_joint_controller.yaml").lexically_normal());
  EXPECT_EQ(first.params[1].ns, "/arm");
  EXPECT_EQ(first.fixed_base, std::optional<bool>(true));
  EXPECT_EQ(first.self_collide, std::optional<bool>(true));
  EXPECT_EQ(first.pose, (std::optional<std::array<double, 6>>(std::array<double, 6>{1, 2, 3, 0.1, 0.2, 0.3})));
  const RobotSpec& second = launch.robots[1];
  ASSERT_EQ(second.params.size(), 1u);
  EXPECT_EQ(second.params[0].ns, "/a/b");
  EXPECT_FALSE(second.fixed_base.has_value());
  EXPECT_FALSE(second.self_collide.has_value());
  EXPECT_EQ(second.pose, (std::optional<std::array<double, 6>>(std::array<double, 6>{0, 0, 0.5, 0, 0, 0})));
}

TEST(LaunchFile, MissingFileIsNamed) {
  try {
    loadLaunchFile(kOneDof / "no_such.launch.yaml");
    FAIL() << "no error";
  } catch (const servoloop::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such.launch.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos);
  }
}

TEST(PubFlag, NumberAtTime) {
  const TimedPublication publication = parsePubFlag("/one_DOF_robot/joint1_position_controller/command:=1.0@2.5");
  EXPECT_EQ(publication.topic, "/one_DOF_robot/joint1_position_controller/command");
  EXPECT_EQ(publication.type, "std_msgs/Float64");
  EXPECT_DOUBLE_EQ(publication.message.get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(publication.time_s, 2.5);
}

TEST(PubFlag, ArrayDefaultsToTimeZero) {
  const TimedPublication publication = parsePubFlag("robot/group/command:=[1, -2.5]");
  EXPECT_EQ(publication.topic, "/robot/group/command");
  EXPECT_EQ(publication.type, "std_msgs/Float64MultiArray");
  EXPECT_EQ(publication.message, nlohmann::json::parse("[1, -2.5]"));
  EXPECT_DOUBLE_EQ(publication.time_s, 0.0);
}

TEST(PubFlag, Errors) {
  EXPECT_NE(flagErrorOf("/a/command=1.0").find("expected TOPIC[:TYPE]:=VALUE[@TIME]"), std::string::npos);
  EXPECT_NE(flagErrorOf(":=1.0").find("expected TOPIC[:TYPE]:=VALUE[@TIME]"), std::string::npos);
  EXPECT_NE(flagErrorOf("/a:=1.0@soon").find("TIME 'soon'"), std::string::npos);
  EXPECT_NE(flagErrorOf("/a:=1.0@-1").find("TIME '-1'"), std::string::npos);
  EXPECT_NE(flagErrorOf("/a:std_msgs/Float64:={data: x}").find("--pub '/a:std_msgs/Float64:={data: x}'"),
            std::string::npos);
  EXPECT_NE(flagErrorOf("/a:std_msgs/Float6:=1.0").find("unknown message type 'std_msgs/Float6'"), std::string::npos);
  EXPECT_NE(flagErrorOf("/a::=1.0").find("expected TOPIC[:TYPE]:=VALUE[@TIME]"), std::string::npos);
}

// A message of any known type, named after the topic as `TOPIC:TYPE:=VALUE`.
TEST(PubFlag, TypeAfterTheTopic) {
  const TimedPublication publication = parsePubFlag(
      "/arm/traj/command:trajectory_msgs/JointTrajectory:={joint_names: [j1, j2], "
      "points: [{positions: [0.5, -0.25], time_from_start: 2.0}]}@1.5");
  EXPECT_EQ(publication.topic, "/arm/traj/command");
  EXPECT_EQ(publication.type, "trajectory_msgs/JointTrajectory");
  EXPECT_FALSE(publication.type_inferred);
  EXPECT_EQ(publication.message["joint_names"], nlohmann::json::parse(R"(["j1", "j2"])"));
  EXPECT_DOUBLE_EQ(publication.message["points"][0]["positions"][1].get<double>(), -0.25);
  EXPECT_DOUBLE_EQ(publication.time_s, 1.5);
  // A typed publication keeps its type whatever the topic carries.
  EXPECT_EQ(withTopicType(publication, "std_msgs/Float64").type, "trajectory_msgs/JointTrajectory");
}

// Without a type, a message with fields takes the type its topic carries (a
// Float64 when the topic carries nothing yet). The value is checked against
// that type then, and the error names the flag.
TEST(PubFlag, WithoutATypeTakesTheTopicsType) {
  const TimedPublication trajectory =
      parsePubFlag("/arm/traj/command:={joint_names: [j1], points: [{positions: [1.0], time_from_start: 2.0}]}");
  EXPECT_TRUE(trajectory.type_inferred);
  const TimedPublication typed = withTopicType(trajectory, "trajectory_msgs/JointTrajectory");
  EXPECT_EQ(typed.type, "trajectory_msgs/JointTrajectory");
  EXPECT_FALSE(typed.type_inferred);
  EXPECT_DOUBLE_EQ(typed.message["points"][0]["positions"][0].get<double>(), 1.0);

  // A number and a list keep their types (a list on a Float64 topic is refused
  // for its type at launch, with the topic's type in the error).
  EXPECT_FALSE(parsePubFlag("/a:=2.0").type_inferred);
  EXPECT_EQ(withTopicType(parsePubFlag("/a:=2.0"), "").type, "std_msgs/Float64");
  EXPECT_EQ(withTopicType(parsePubFlag("/a:=[1, 2]"), "std_msgs/Float64").type, "std_msgs/Float64MultiArray");
  EXPECT_EQ(withTopicType(parsePubFlag("/a:={data: 2.0}"), "").type, "std_msgs/Float64");
  try {
    withTopicType(trajectory, "");  // a trajectory on a topic nobody declared: not a Float64
    ADD_FAILURE() << "a trajectory value was taken as std_msgs/Float64";
  } catch (const servoloop::Error& e) {
    EXPECT_NE(std::string(e.what()).find("--pub '/arm/traj/command:="), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("std_msgs/Float64"), std::string::npos) << e.what();
  }
}

TEST(RecordFlag, TopicAndRelativeFile) {
  const RecordSpec record = parseRecordFlag("/one_DOF_robot/joint_states=out/js.csv");
  EXPECT_EQ(record.topic, "/one_DOF_robot/joint_states");
  EXPECT_EQ(record.file, (fs::current_path() / "out" / "js.csv").lexically_normal());
  EXPECT_NE(flagErrorOf("/one_DOF_robot/joint_states", true).find("expected TOPIC=FILE.csv"), std::string::npos);
  EXPECT_NE(flagErrorOf("=a.csv", true).find("expected TOPIC=FILE.csv"), std::string::npos);
}

}  // namespace
