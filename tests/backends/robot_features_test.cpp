// ROS robots as users bring them, run with the built `servoloop launch` (a
// child process) on bullet and mujoco, each result checked against geometry
// worked out by hand:
//
//  - self-collision is off unless asked for (Gazebo's default): two sliding
//    fingers (tests/assets/features/fingers.urdf) pass through each other to
//    finger_a's 0.6 m limit; with `self_collide: true` in the launch file, or
//    <gazebo><self_collide>true</self_collide></gazebo> in the URDF, finger_a
//    stops where the boxes touch, 0.4 m (+ finger_b's 1 mm of travel);
//  - the same robot loads although it carries a massless moving link, a
//    <verbose> element, a pre-2015 transmission and an unknown transmission
//    type, each with its warning; its controllers sit at the top level of
//    their YAML, loaded into the namespace by `params: [{file, ns}]`;
//  - bases: `fixed_base: true` holds a robot whose root has mass, and the
//    spawn pose turns it (pitch pi/2 makes the pendulum rest at q = -pi/2); a
//    root link without mass is a fixed base (pybullet's convention), with a note;
//  - a robot spawned with a link in the floor gets a warning naming the link,
//    how deep it is and the height to spawn it at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kAssets = fs::path(SERVOLOOP_SOURCE_DIR) / "tests" / "assets" / "features";

struct CliResult {
  int status = -1;
  std::string out;
  std::string err;
};

class FeatureRun : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
#ifndef SERVOLOOP_HAVE_MUJOCO
    if (GetParam() == "mujoco") GTEST_SKIP() << "the mujoco backend is not built here";
#endif
#ifndef SERVOLOOP_HAVE_BULLET
    if (GetParam() == "bullet") GTEST_SKIP() << "the bullet backend is not built here";
#endif
  }

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = temp_.path() / name;
    std::ofstream(file) << text;
    return file;
  }

  CliResult launch(const fs::path& launch_file, const std::string& flags) const {
    const auto result = servoloop::testing::runShell(
        std::string("exec '") + SERVOLOOP_CLI_EXE + "' launch '" + launch_file.string() + "' --backend " +
            GetParam() + " --json " + flags,
        {temp_.path(), temp_.path(),
         {{"SERVOLOOP_PLUGIN_PATH", std::nullopt}, {"SERVOLOOP_RUN_DIR", temp_.path().string()}}},
        300.0);
    EXPECT_FALSE(result.timed_out) << flags;
    return {result.status, result.out, result.err};
  }

  // The final state of `joint` in a run's JSON summary.
  static json joint(const CliResult& result, const std::string& name) {
    const json summary = json::parse(result.out);
    for (const json& j : summary["robots"][0]["joints"]) {
      if (j["name"] == name) return j;
    }
    ADD_FAILURE() << "no joint '" << name << "' in " << result.out;
    return json{{"position", NAN}, {"velocity", NAN}};
  }

  // The fingers in a world without gravity; finger_a pushed by 5 N.
  fs::path fingersLaunch(const std::string& urdf, const std::string& robot_extra) const {
    return write("fingers.launch.yaml", R"(world:
  gravity: [0, 0, 0]
robots:
  - urdf: ')" + urdf + R"('
    namespace: /fingers
    params: [{file: ')" + (kAssets / "fingers_controllers.yaml").string() + R"(', ns: /fingers}]
    controllers: [joint_state_controller, finger_a_effort]
)" + robot_extra + R"(
publish:
  - {topic: /fingers/finger_a_effort/command, value: 5.0}
)");
  }

  servoloop::testing::TempDir temp_{"servoloop-features"};
};

// Where finger_a ends: pushed with 5 N against 2 N·s/m of damping it moves at
// up to 2.5 m/s and covers 0.6 m well within the 2 s run.
constexpr double kFingerLimit = 0.6;
constexpr double kFingersTouch = 0.4;  // 0.5 m between centres − two half-widths of 0.05 m
// finger_b's 1 mm of travel, plus contact margin and penetration: bullet's
// hull margin is 1 mm, mujoco's soft contact sinks a few mm under 5 N.
constexpr double kContactTolerance = 0.01;

TEST_P(FeatureRun, FingersPassThroughEachOtherWithoutSelfCollision) {
  const CliResult result = launch(fingersLaunch((kAssets / "fingers.urdf").string(), ""), "--duration 2");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NEAR(joint(result, "finger_a_slide")["position"].get<double>(), kFingerLimit, 2e-3) << result.err;

  // The description loaded although Gazebo-only tolerance was needed; each
  // thing skipped or taken over is said once, naming the element and the fix.
  EXPECT_NE(result.err.find("link 'camera' (moved by joint 'camera_pan') has no <inertial>"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("unknown type 'transmission_interface/BeltTransmission'"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("deprecated pre-2015 form"), std::string::npos) << result.err;
  const json summary = json::parse(result.out);
  for (const json& j : summary["robots"][0]["joints"]) EXPECT_NE(j["name"], "camera_pan") << result.out;
}

TEST_P(FeatureRun, LaunchFileSelfCollideStopsTheFingersWhereTheyTouch) {
  const CliResult result =
      launch(fingersLaunch((kAssets / "fingers.urdf").string(), "    self_collide: true\n"), "--duration 2");
  ASSERT_EQ(result.status, 0) << result.err;
  const double a = joint(result, "finger_a_slide")["position"].get<double>();
  const double b = joint(result, "finger_b_slide")["position"].get<double>();
  EXPECT_NEAR(a - b, kFingersTouch, kContactTolerance);
  EXPECT_GT(b, -kContactTolerance);
  EXPECT_LT(b, 0.001 + kContactTolerance);
}

TEST_P(FeatureRun, UrdfGazeboSelfCollideStopsTheFingersToo) {
  std::ifstream in(kAssets / "fingers.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  urdf.replace(urdf.rfind("</robot>"), 8, "<gazebo><self_collide>true</self_collide></gazebo></robot>");
  const CliResult result = launch(fingersLaunch(write("fingers_self.urdf", urdf).string(), ""), "--duration 2");
  ASSERT_EQ(result.status, 0) << result.err;
  const double a = joint(result, "finger_a_slide")["position"].get<double>();
  const double b = joint(result, "finger_b_slide")["position"].get<double>();
  EXPECT_NEAR(a - b, kFingersTouch, kContactTolerance);
}

TEST_P(FeatureRun, FixedBaseAndSpawnPoseTurnTheHanger) {
  const fs::path file = write("hanger.launch.yaml", R"(robots:
  - urdf: ')" + (kAssets / "hanger.urdf").string() + R"('
    fixed_base: true
    pose: [0.3, -0.2, 2.0, 0, 1.5707963267948966, 0]
)");
  const CliResult result = launch(file, "--duration 12");
  ASSERT_EQ(result.status, 0) << result.err;
  // Damping ratio ~0.23 at ~4.4 rad/s: the swing decays as e^(−t); after 12 s
  // it is below 1e-5 rad.
  EXPECT_NEAR(joint(result, "swing")["position"].get<double>(), -std::numbers::pi / 2, 1e-3);
}

// A robot spawned with its foot in the floor is thrown up at the first step
// by either engine; the launch says so and how high to spawn it. The hopper
// (tests/assets/features/hopper.urdf): a 0.2 m cube on a hip 0.1 m below its
// centre, a 0.4 m leg, a ball of 0.05 m radius welded to its end: at z = 0.3
// the ball's bottom is 0.25 m under.
TEST_P(FeatureRun, ARobotSpawnedIntoTheFloorIsNamedWithTheHeightToSpawnItAt) {
  const fs::path urdf = kAssets / "hopper.urdf";
  const auto spawnedAt = [&](const fs::path& robot, double z) {
    return launch(write("hopper.launch.yaml", "world: {ground_plane: true}\nrobots:\n  - urdf: '" + robot.string() +
                                                  "'\n    pose: [0, 0, " + std::to_string(z) + "]\n"),
                  "--duration 0.01");
  };
  const CliResult in_floor = spawnedAt(urdf, 0.3);
  ASSERT_EQ(in_floor.status, 0) << in_floor.err;
  EXPECT_NE(in_floor.err.find("link 'foot' starts 0.250 m below the ground plane"), std::string::npos)
      << in_floor.err;
  EXPECT_NE(in_floor.err.find("a root z of at least 0.550 m"), std::string::npos) << in_floor.err;
  // Standing on the ball (its bottom at 0.005 m) says nothing.
  const CliResult standing = spawnedAt(urdf, 0.555);
  ASSERT_EQ(standing.status, 0) << standing.err;
  EXPECT_EQ(standing.err.find("below the ground plane"), std::string::npos) << standing.err;
  // Hung from a root link 'world' 0.3 m up: the spawn pose moves the world
  // link too (as Gazebo places such a robot), so at z = 0 the foot is 0.25 m
  // under and the warning offers z = 0.25; at z = 0.6 it hangs clear.
  std::ifstream in(urdf);
  std::string hung_xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  hung_xml.insert(hung_xml.find("<link name=\"base\">"),
                  "<link name=\"world\"/><joint name=\"mount\" type=\"fixed\"><parent link=\"world\"/>"
                  "<child link=\"base\"/><origin xyz=\"0 0 0.3\"/></joint>\n  ");
  const fs::path hung = write("hung_hopper.urdf", hung_xml);
  const CliResult low = spawnedAt(hung, 0.0);
  ASSERT_EQ(low.status, 0) << low.err;
  EXPECT_NE(low.err.find("link 'foot' starts 0.250 m below the ground plane"), std::string::npos) << low.err;
  EXPECT_NE(low.err.find("a root z of at least 0.250 m"), std::string::npos) << low.err;
  const CliResult hanging = spawnedAt(hung, 0.6);
  ASSERT_EQ(hanging.status, 0) << hanging.err;
  EXPECT_EQ(hanging.err.find("below the ground plane"), std::string::npos) << hanging.err;
}

TEST_P(FeatureRun, RootWithoutMassIsAFixedBaseWithANote) {
  std::ifstream in(kAssets / "hanger.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto begin = urdf.find("<inertial>");
  urdf.erase(begin, urdf.find("</inertial>") + 11 - begin);  // the mount's
  const fs::path file = write("hanger.launch.yaml", R"(robots:
  - urdf: ')" + write("static_hanger.urdf", urdf).string() + R"('
    pose: [0, 0, 2.0, 0, 1.5707963267948966, 0]
)");
  const CliResult result = launch(file, "--duration 12");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NEAR(joint(result, "swing")["position"].get<double>(), -std::numbers::pi / 2, 1e-3);
  EXPECT_NE(result.err.find("root link 'mount' has no mass, so the base is fixed"), std::string::npos)
      << result.err;
}

// The root namespace, as a robot launched without <group ns>: controllers
// of a top-level YAML loaded at "/" run, their topics are at the root.
TEST_P(FeatureRun, RobotInTheRootNamespace) {
  const fs::path file = write("root.launch.yaml", R"(world:
  gravity: [0, 0, 0]
robots:
  - urdf: ')" + (kAssets / "fingers.urdf").string() + R"('
    namespace: /
    params: [')" + (kAssets / "fingers_controllers.yaml").string() + R"(']
    controllers: [joint_state_controller, finger_a_effort]
publish:
  - {topic: /finger_a_effort/command, value: 5.0}
)");
  const CliResult result = launch(file, "--duration 2");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out)["robots"][0]["namespace"], "/");
  EXPECT_NEAR(joint(result, "finger_a_slide")["position"].get<double>(), kFingerLimit, 2e-3) << result.err;
}

// An effort limit of 0 leaves a joint that nothing drives, through any
// interface (the start-up warning says so): the hanger's swing under a
// position controller commanded to 1 rad stays hanging at 0; without the
// limit the position motor takes it to 1 rad.
TEST_P(FeatureRun, AnEffortLimitOfZeroDrivesNothing) {
  std::ifstream in(kAssets / "hanger.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string limited = [&] {
    std::string text = urdf;
    text.insert(text.find("<dynamics damping"), "<limit effort=\"0\" velocity=\"10\"/>\n    ");
    return text;
  }();
  const fs::path params = write("hold.yaml", R"(hanger:
  hold: {type: position_controllers/JointPositionController, joint: swing}
)");
  const auto run = [&](const std::string& name, const std::string& text) {
    const fs::path file = write(name + ".launch.yaml", R"(robots:
  - urdf: ')" + write(name + ".urdf", text).string() + R"('
    namespace: /hanger
    fixed_base: true
    pose: [0, 0, 2, 0, 0, 0]
    params: [')" + params.string() + R"(']
    controllers: [hold]
publish:
  - {topic: /hanger/hold/command, value: 1.0}
)");
    return launch(file, "--duration 2");
  };
  const CliResult held = run("free", urdf);
  ASSERT_EQ(held.status, 0) << held.err;
  EXPECT_NEAR(joint(held, "swing")["position"].get<double>(), 1.0, 1e-3);
  const CliResult stuck = run("zero_effort", limited);
  ASSERT_EQ(stuck.status, 0) << stuck.err;
  EXPECT_NEAR(joint(stuck, "swing")["position"].get<double>(), 0.0, 1e-3);
  EXPECT_NE(stuck.err.find("has an effort limit of 0"), std::string::npos) << stuck.err;
}

// A controller file loaded at "/" while the robot has its own namespace: the
// error says where the controller's type was found and how to load it there.
TEST_P(FeatureRun, ControllersLoadedOutsideTheNamespaceAreFoundForTheError) {
  const fs::path file = write("wrong_ns.launch.yaml", R"(robots:
  - urdf: ')" + (kAssets / "fingers.urdf").string() + R"('
    namespace: /fingers
    params: [')" + (kAssets / "fingers_controllers.yaml").string() + R"(']
    controllers: [finger_a_effort]
)");
  const CliResult result = launch(file, "--duration 0.1");
  EXPECT_EQ(result.status, 1) << result.err;
  EXPECT_NE(result.err.find("load controller 'finger_a_effort': parameter '/fingers/finger_a_effort/type' is "
                            "missing, but the parameters have '/finger_a_effort/type'"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("ns: /fingers"), std::string::npos) << result.err;
  // One error for the load, with the fix in it: not the manager's generic
  // "add 'type:'" as well.
  EXPECT_EQ(result.err.find("add 'type: <package>/<Controller>'"), std::string::npos) << result.err;

  // A file that already nests its controllers under the robot's name, loaded
  // into the namespace as well: the hint says to drop the ns:, not to add it.
  const fs::path nested = write("nested_ns.launch.yaml", R"(robots:
  - urdf: ')" + (kAssets / "fingers.urdf").string() + R"('
    namespace: /fingers
    params: [{file: ')" + (kAssets / "fingers_controllers.yaml").string() + R"(', ns: /fingers/fingers}]
    controllers: [finger_a_effort]
)");
  const CliResult twice = launch(nested, "--duration 0.1");
  EXPECT_EQ(twice.status, 1) << twice.err;
  EXPECT_NE(twice.err.find("the parameters have '/fingers/fingers/finger_a_effort/type': the file nests its "
                           "controllers under 'fingers:'"),
            std::string::npos)
      << twice.err;
  EXPECT_NE(twice.err.find("load it without `ns:`"), std::string::npos) << twice.err;
  EXPECT_EQ(twice.err.find("ns: /fingers}"), std::string::npos) << twice.err;
}

// A floating robot's ground truth (nav_msgs/Odometry on
// <ns>/ground_truth/odom): the hanger dropped from 1 m, at rest, falls freely
// (its pendulum does not swing in a uniform field), so its root frame follows
// z(t) = 1 − g t²/2 with velocity −g t, orientation unchanged.
TEST_P(FeatureRun, FloatingBaseGroundTruthFollowsFreeFall) {
  const fs::path file = write("drop.launch.yaml", R"(robots:
  - urdf: ')" + (kAssets / "hanger.urdf").string() + R"('
    namespace: /hanger
    pose: [0, 0, 1, 0, 0, 0]
)");
  const CliResult result = launch(file, "--duration 0.3 --record /hanger/ground_truth/odom=odom.csv");
  ASSERT_EQ(result.status, 0) << result.err;
  std::ifstream csv(temp_.path() / "odom.csv");
  std::string header;
  std::getline(csv, header);
  std::vector<std::string> columns;
  for (std::size_t at = 0, next; at != std::string::npos; at = next == std::string::npos ? next : next + 1) {
    next = header.find(',', at);
    columns.push_back(header.substr(at, next == std::string::npos ? std::string::npos : next - at));
  }
  const auto column = [&](const std::string& name) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    EXPECT_NE(it, columns.end()) << name << " not in " << header;
    return static_cast<std::size_t>(it - columns.begin());
  };
  const std::size_t time = column("time"), z = column("pose.position.z"), vz = column("twist.linear.z"),
                    qw = column("pose.orientation.w"), child = column("child_frame_id");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) {
    std::vector<std::string> cells;
    for (std::size_t at = 0, next; at != std::string::npos; at = next == std::string::npos ? next : next + 1) {
      next = line.find(',', at);
      cells.push_back(line.substr(at, next == std::string::npos ? std::string::npos : next - at));
    }
    ASSERT_EQ(cells.size(), columns.size()) << line;
    const double t = std::stod(cells[time]);
    // Semi-implicit Euler (bullet) leads the exact fall by dt·|v| ≤ 3e-3 m at 0.3 s.
    EXPECT_NEAR(std::stod(cells[z]), 1.0 - 0.5 * 9.81 * t * t, 3.5e-3) << "t = " << t;
    EXPECT_NEAR(std::stod(cells[vz]), -9.81 * t, 1.5e-2) << "t = " << t;
    EXPECT_NEAR(std::stod(cells[qw]), 1.0, 1e-9);
    EXPECT_EQ(cells[child], "mount");
    ++rows;
  }
  EXPECT_GE(rows, 14) << "50 Hz over 0.3 s";
}

// A batch run whose launch file asks for a controller that does not load
// (no such parameters) still runs and reports, then exits non-zero naming it.
TEST_P(FeatureRun, BatchRunWithAControllerThatDoesNotLoadExitsNonZero) {
  const fs::path file = write("hanger.launch.yaml", R"(robots:
  - urdf: ')" + (kAssets / "hanger.urdf").string() + R"('
    fixed_base: true
    controllers: [no_such_controller]
)");
  const CliResult result = launch(file, "--duration 0.1");
  EXPECT_EQ(result.status, 1) << result.err;
  EXPECT_NE(result.err.find("controller 'no_such_controller' did not load"), std::string::npos) << result.err;
  const json summary = json::parse(result.out);
  EXPECT_EQ(summary["robots"][0]["launch_failures"][0], "controller 'no_such_controller' did not load");
}

INSTANTIATE_TEST_SUITE_P(Backends, FeatureRun, ::testing::Values("bullet", "mujoco"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
