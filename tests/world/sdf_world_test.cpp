// SDFormat worlds (description/sdf_world.hpp, node/sdf_world_launch.hpp):
// Gazebo's world files read with libsdformat, checked against hand
// calculations (a joint placed where the SDF poses put it) and against
// closed-form physics on bullet and mujoco (a box sliding to rest after
// v^2 / (2 mu g); a box resting on a static table).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/sdf_world.hpp"
#include "servoloop/node/launch_file.hpp"
#include "servoloop/node/node.hpp"
#include "temp_dir.hpp"
#include "world_test_support.hpp"

namespace servoloop::world_test {
namespace {

namespace fs = std::filesystem;
using node::ModelState;
using node::ModelTwist;
using node::Node;
using node::NodeOptions;
using servoloop::testing::TempDir;
using servoloop::testing::writeFile;

constexpr double kGravity = 9.81;

// A 0.2 m, 1 kg box model with friction mu at (x, y, z).
std::string boxModel(const std::string& name, double x, double y, double z, double mu, bool is_static = false) {
  const double side = 0.2;
  const double inertia = side * side / 6.0;
  return "<model name='" + name + "'><static>" + (is_static ? "true" : "false") + "</static><pose>" +
         std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) +
         " 0 0 0</pose><link name='body'><inertial><mass>1</mass><inertia><ixx>" + std::to_string(inertia) +
         "</ixx><iyy>" + std::to_string(inertia) + "</iyy><izz>" + std::to_string(inertia) +
         "</izz></inertia></inertial><collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry>"
         "<surface><friction><ode><mu>" + std::to_string(mu) + "</mu><mu2>" + std::to_string(mu) +
         "</mu2></ode></friction></surface></collision><visual name='v'><geometry><box><size>0.2 0.2 0.2</size>"
         "</box></geometry><material><diffuse>0.8 0.4 0.1 1</diffuse></material></visual></link></model>";
}

fs::path writeWorld(const fs::path& dir, const std::string& models, const std::string& extra = "") {
  const fs::path file = dir / "test.world";
  writeFile(file, "<?xml version='1.0'?>\n<sdf version='1.6'><world name='default'>\n"
                  "<include><uri>model://ground_plane</uri></include>\n"
                  "<include><uri>model://sun</uri></include>\n"
                  "<physics type='ode'><max_step_size>0.001</max_step_size><real_time_factor>1</real_time_factor>"
                  "</physics>\n" +
                      extra + models + "\n</world></sdf>\n");
  return file;
}

class SdfWorldPhysics : public ::testing::TestWithParam<std::string> {};

// Given 2 m/s along x on the ground with mu = 0.5, a box slides to rest after
// v^2 / (2 mu g) = 0.408 m (Coulomb friction, as Gazebo's ODE gives it), within 3 %.
TEST_P(SdfWorldPhysics, ABoxSlidesToRestAfterTheCoulombDistance) {
  const std::string backend = GetParam();
#ifndef SERVOLOOP_TEST_MUJOCO
  if (backend == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  TempDir dir("servoloop-sdf-slide-" + backend);
  node::LaunchFile launch = node::loadLaunchFile(writeWorld(dir.path(), boxModel("crate", 0, 0, 0.1, 0.5)));
  launch.world.backend = backend;
  ASSERT_TRUE(launch.world.ground_plane) << "model://ground_plane is the world's ground";
  ASSERT_EQ(launch.robots.size(), 1u);
  Node world(launch, pausedOptions());
  world.start();
  ASSERT_EQ(world.stepWorld(200), 200u);  // settled on the ground
  const ModelState rest = world.modelState("crate");
  EXPECT_NEAR(rest.position[2], 0.1, 2e-3);
  ModelTwist push;
  push.linear[0] = 2.0;
  world.setModelState("crate", std::nullopt, push);
  const double v = 2.0;
  const double mu = 0.5;
  const double expected = v * v / (2 * mu * kGravity);
  // Until it stands (0.41 s of sliding), in 10 ms steps.
  ModelState now = world.modelState("crate");
  for (int i = 0; i < 200 && (i < 5 || std::abs(now.linear_velocity[0]) > 1e-4); ++i) {
    ASSERT_EQ(world.stepWorld(10), 10u);
    now = world.modelState("crate");
  }
  EXPECT_LT(std::abs(now.linear_velocity[0]), 1e-3) << "still sliding";
  EXPECT_NEAR(now.position[0] - rest.position[0], expected, 0.03 * expected);
  EXPECT_NEAR(now.position[1], rest.position[1], 1e-3) << "slid off its line";
}

// A box on a static table (a one-link static model): it rests there, moving
// less than 1 mm in 10 s.
TEST_P(SdfWorldPhysics, ABoxRestsOnAStaticTable) {
  const std::string backend = GetParam();
#ifndef SERVOLOOP_TEST_MUJOCO
  if (backend == "mujoco") GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  TempDir dir("servoloop-sdf-table-" + backend);
  const std::string table =
      "<model name='table'><static>true</static><pose>1 0 0.475 0 0 0</pose><link name='top'>"
      "<collision name='c'><geometry><box><size>1 1 0.05</size></box></geometry></collision></link></model>";
  node::LaunchFile launch = node::loadLaunchFile(writeWorld(dir.path(), table + boxModel("crate", 1, 0, 0.6, 0.8)));
  launch.world.backend = backend;
  Node world(launch, pausedOptions());
  world.start();
  ASSERT_EQ(world.stepWorld(500), 500u);
  const ModelState settled = world.modelState("crate");
  EXPECT_NEAR(settled.position[2], 0.6, 2e-3) << "on the table top (z 0.5) with its half height 0.1";
  EXPECT_TRUE(world.modelState("table").fixed);
  ASSERT_EQ(world.stepWorld(10000), 10000u);
  const ModelState later = world.modelState("crate");
  const double drift = std::hypot(later.position[0] - settled.position[0], later.position[1] - settled.position[1],
                                  later.position[2] - settled.position[2]);
  EXPECT_LT(drift, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Engines, SdfWorldPhysics, ::testing::Values("bullet", "mujoco"));

// A pendulum model whose joint sits 0.3 m below its canonical link and whose
// arm link is posed in the model frame: the URDF puts the arm's frame at the
// joint, 0.3 m below the base, with the axis the SDF gives; the arm's
// collision 0.25 m further down.
TEST(SdfWorld, JointsAndPosesBecomeTheUrdfOfTheModel) {
  TempDir dir("servoloop-sdf-pendulum");
  const std::string pendulum =
      "<model name='pendulum'><pose>0 0 1 0 0 0</pose>"
      "<link name='base'><inertial><mass>1</mass></inertial>"
      "<collision name='c'><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision></link>"
      "<link name='arm'><pose>0 0 -0.3 0 0 0</pose><inertial><pose>0 0 -0.25 0 0 0</pose><mass>0.5</mass>"
      "</inertial><collision name='rod'><pose>0 0 -0.25 0 0 0</pose><geometry><cylinder><radius>0.02</radius>"
      "<length>0.5</length></cylinder></geometry></collision></link>"
      "<joint name='hinge' type='revolute'><parent>base</parent><child>arm</child>"
      "<axis><xyz>0 1 0</xyz><limit><lower>-1.5</lower><upper>1.5</upper><effort>10</effort>"
      "<velocity>3</velocity></limit><dynamics><damping>0.1</damping></dynamics></axis></joint></model>";
  const SdfWorld sdf = readSdfWorld(writeWorld(dir.path(), pendulum));
  ASSERT_EQ(sdf.models.size(), 1u);
  const SdfWorldModel& model = sdf.models.front();
  EXPECT_FALSE(model.fixed_base);
  EXPECT_DOUBLE_EQ(model.pose[2], 1.0) << "the root link stands where the model does";
  const auto urdf = parseRobotModel(model.urdf, "pendulum");
  const auto joint = urdf->getJoint("hinge");
  ASSERT_NE(joint, nullptr);
  EXPECT_EQ(joint->type, urdf::Joint::REVOLUTE);
  EXPECT_NEAR(joint->parent_to_joint_origin_transform.position.z, -0.3, 1e-12);
  EXPECT_NEAR(joint->axis.y, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(joint->limits->lower, -1.5);
  EXPECT_DOUBLE_EQ(joint->limits->effort, 10.0);
  EXPECT_DOUBLE_EQ(joint->dynamics->damping, 0.1);
  const auto arm = urdf->getLink("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_NEAR(arm->collision->origin.position.z, -0.25, 1e-12);
  EXPECT_NEAR(arm->inertial->origin.position.z, -0.25, 1e-12);
  EXPECT_DOUBLE_EQ(arm->inertial->mass, 0.5);
}

// What servoloop does not simulate is one warning each; what it cannot read
// is one error naming the file and line.
TEST(SdfWorld, LightsSensorsAndPluginsAreOneWarningEachAndErrorsNameTheLine) {
  TempDir dir("servoloop-sdf-warnings");
  const std::string with_sensor =
      "<model name='probe'><link name='body'><inertial><mass>1</mass></inertial>"
      "<sensor name='imu' type='imu'/></link>"
      "<plugin name='mover' filename='libmover.so'/></model>";
  const SdfWorld sdf =
      readSdfWorld(writeWorld(dir.path(), with_sensor, "<plugin name='w' filename='libworld.so'/>"));
  std::vector<std::string> expected = {"light 'sun'", "sensor 'imu'", "plugin 'mover'", "plugin 'w'"};
  for (const std::string& what : expected) {
    int count = 0;
    for (const std::string& warning : sdf.warnings) count += warning.find(what) != std::string::npos;
    EXPECT_EQ(count, 1) << what;
  }
  EXPECT_EQ(sdf.warnings.size(), expected.size());

  const fs::path broken = dir.path() / "broken.world";
  writeFile(broken, "<?xml version='1.0'?>\n<sdf version='1.6'>\n<world name='w'>\n<model name='m'>\n"
                    "<link name='a'><pose>1 2</pose></link>\n</model>\n</world>\n</sdf>\n");
  try {
    (void)node::loadLaunchFile(broken);
    ADD_FAILURE() << "a broken world was read";
  } catch (const ConfigError& e) {
    // libsdformat's own words, with the file and line of the bad element.
    EXPECT_NE(std::string(e.what()).find("must have 6 values, but 2 were found"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(broken.string() + ":5:"), std::string::npos) << e.what();
  }
  const fs::path ball = dir.path() / "ball.world";
  writeFile(ball, "<?xml version='1.0'?><sdf version='1.6'><world name='w'><model name='m'>"
                  "<link name='a'><inertial><mass>1</mass></inertial></link>"
                  "<link name='b'><inertial><mass>1</mass></inertial></link>"
                  "<joint name='j' type='ball'><parent>a</parent><child>b</child></joint></model></world></sdf>");
  try {
    (void)readSdfWorld(ball);
    ADD_FAILURE() << "a ball joint was read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("model 'm' joint 'j': a ball joint"), std::string::npos) << e.what();
  }
}

// A YAML launch file's world: {file:} brings the world's models beside its
// own robots, its own world keys winning; a ROS launch file including
// gazebo_ros's empty_world.launch with world_name loads that world.
TEST(SdfWorld, LaunchFilesNameAWorldFile) {
  TempDir dir("servoloop-sdf-launch");
  const fs::path world = writeWorld(dir.path(), boxModel("crate", 0, 0, 0.1, 0.5) + boxModel("pallet", 1, 0, 0.1, 0.5));
  const fs::path seed = fs::path(SERVOLOOP_SOURCE_DIR) / "robots" / "one_dof";
  const fs::path yaml = dir.path() / "with_world.launch.yaml";
  writeFile(yaml, "world: {file: test.world, time_step: 0.002, shared: false}\nrobots:\n  - urdf: " +
                      (seed / "minimal_robot_description_w_jnt_ctl.urdf").string() + "\n");
  const node::LaunchFile launch = node::loadLaunchFile(yaml);
  ASSERT_EQ(launch.robots.size(), 3u);
  EXPECT_EQ(launch.robots[0].model, "crate");
  EXPECT_EQ(launch.robots[1].model, "pallet");
  EXPECT_EQ(launch.world.time_step_s, 0.002) << "the launch file's own key wins";
  EXPECT_TRUE(launch.world.ground_plane);
  EXPECT_FALSE(launch.world.shared);

  const fs::path ros = dir.path() / "gazebo.launch";
  writeFile(ros, "<launch><include file=\"$(find gazebo_ros)/launch/empty_world.launch\">"
                 "<arg name=\"world_name\" value=\"" + world.string() + "\"/></include></launch>");
  const node::LaunchFile from_ros = node::loadLaunchFile(ros);
  ASSERT_EQ(from_ros.robots.size(), 2u);
  EXPECT_EQ(from_ros.robots[1].model, "pallet");
}

}  // namespace
}  // namespace servoloop::world_test
