// Rigid-body side of BulletWorld: fixed children merged into their parent,
// a floating base in free fall and on the ground, STL collision meshes.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reference_ode.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_bullet/bullet_world.hpp"

namespace servoloop::sim_bullet {
namespace {

using testing::integrateRk4;

constexpr double kG = 9.81;
const std::string kAssetsDir = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/";

double sq(double x) { return x * x; }

// A rod on a hinge with a bob welded to its end (fixed joint, rotated 90 deg about z).
const char* kWeldedBobUrdf = R"(<robot name="welded_pendulum"><link name="world"/>
  <joint name="hinge" type="continuous"><parent link="world"/><child link="rod"/>
    <origin xyz="0 0 2"/><axis xyz="0 1 0"/></joint>
  <link name="rod"><inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/></inertial></link>
  <joint name="weld" type="fixed"><parent link="rod"/><child link="bob"/>
    <origin xyz="0 0 -1" rpy="0 0 1.5707963267948966"/></joint>
  <link name="bob"><inertial><origin xyz="0.1 0 0"/><mass value="2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial></link></robot>)";

// Times at which q crosses zero going down, linearly interpolated.
std::vector<double> downCrossings(const std::vector<double>& q, double dt) {
  std::vector<double> times;
  for (std::size_t k = 1; k < q.size(); ++k) {
    if (q[k - 1] > 0.0 && q[k] <= 0.0) times.push_back(dt * (k - 1 + q[k - 1] / (q[k - 1] - q[k])));
  }
  return times;
}

double meanPeriod(const std::vector<double>& crossings) {
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(BulletWorldBody, WeldedBobIsMergedWithHandComputedMassProperties) {
  BulletWorld world(*parseRobotModel(kWeldedBobUrdf, "welded.urdf"));
  ASSERT_EQ(world.numJoints(), 1u);  // the fixed joint is not a joint of the simulation

  // Hand computation in the rod frame. Bob COM: (0,0,-1) + Rz(90 deg)(0.1,0,0) = (0, 0.1, -1);
  // its inertia in rod axes: Rz diag(0.01, 0.03, 0.02) Rz^T = diag(0.03, 0.01, 0.02).
  const double mass = 1.0 + 2.0;
  const Eigen::Vector3d com = (1.0 * Eigen::Vector3d(0, 0, -0.5) + 2.0 * Eigen::Vector3d(0, 0.1, -1.0)) / mass;
  EXPECT_NEAR(com.y(), 0.2 / 3.0, 1e-15);
  EXPECT_NEAR(com.z(), -2.5 / 3.0, 1e-15);
  // Offsets of each part's COM from the combined COM: rod (0, -1/15, 1/3), bob (0, 1/30, -1/6).
  Eigen::Matrix3d expected_inertia = Eigen::Matrix3d::Zero();
  expected_inertia(0, 0) = 0.02 + 0.03 + 1.0 * (sq(1.0 / 15) + sq(1.0 / 3)) + 2.0 * (sq(1.0 / 30) + sq(1.0 / 6));
  expected_inertia(1, 1) = 0.02 + 0.01 + 1.0 * sq(1.0 / 3) + 2.0 * sq(1.0 / 6);
  expected_inertia(2, 2) = 0.001 + 0.02 + 1.0 * sq(1.0 / 15) + 2.0 * sq(1.0 / 30);
  expected_inertia(1, 2) = expected_inertia(2, 1) = -(1.0 * (-1.0 / 15) * (1.0 / 3) + 2.0 * (1.0 / 30) * (-1.0 / 6));

  for (const char* link : {"rod", "bob"}) {
    const BodyMassProperties merged = world.bodyMassProperties(link);
    EXPECT_NEAR(merged.mass_kg, mass, 1e-12) << link;
    EXPECT_TRUE(merged.com.isApprox(com, 1e-12)) << merged.com.transpose();
    EXPECT_TRUE(merged.inertia.isApprox(expected_inertia, 1e-12)) << merged.inertia;
  }
  // The bob frame hangs 1 m below the rod origin, which is the hinge at z = 2.
  EXPECT_TRUE(world.linkWorldPosition("bob").isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
}

TEST(BulletWorldBody, WeldedBobPendulumPeriodMatchesCombinedInertia) {
  BulletWorld world(*parseRobotModel(kWeldedBobUrdf, "welded.urdf"));
  // About the hinge: I = Iyy_com + M (cx^2 + cz^2) = 0.02 + 1*0.25 + 0.01 + 2*1 = 2.28 kg m^2.
  const double inertia_about_hinge = 0.02 + 1.0 * 0.25 + 0.01 + 2.0 * 1.0;
  const double mass = 3.0, com_z = -2.5 / 3.0;
  const auto acceleration = [&](double q, double) { return mass * kG * com_z * std::sin(q) / inertia_about_hinge; };

  const double q0 = 0.3;
  world.setJointState(0, q0, 0.0);
  const double dt = world.timeStep();
  const double duration = 4.5;  // a little over two periods (about 1.92 s each)
  std::vector<double> simulated{q0};
  while (world.time() < duration - 0.5 * dt) {
    world.step();
    simulated.push_back(world.jointPosition(0));
  }
  std::vector<double> reference;
  for (const auto& s : integrateRk4(acceleration, q0, 0.0, duration, dt)) reference.push_back(s.position);

  const auto sim_crossings = downCrossings(simulated, dt);
  const auto ref_crossings = downCrossings(reference, dt);
  ASSERT_GE(sim_crossings.size(), 2u);
  ASSERT_EQ(sim_crossings.size(), ref_crossings.size());
  // The half-step lag shifts every crossing alike and cancels in the period;
  // the frequency error is O((w dt)^2) ~ 1e-6 relative. Bound 1 ms (0.05 %);
  // forgetting the bob (rod only) would give 1.47 s instead of 1.92 s.
  EXPECT_NEAR(meanPeriod(sim_crossings), meanPeriod(ref_crossings), 1e-3);
}

const char* kFreeBoxUrdf = R"(<robot name="free_box">
  <link name="box"><inertial><mass value="2"/>
    <inertia ixx="0.013333" ixy="0" ixz="0" iyy="0.013333" iyz="0" izz="0.013333"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>)";

TEST(BulletWorldBody, FloatingBoxFallsFreely) {
  WorldSettings settings;
  settings.initial_base_position = Eigen::Vector3d(0.3, -0.2, 5.0);
  BulletWorld world(*parseRobotModel(kFreeBoxUrdf, "box.urdf"), settings);
  EXPECT_FALSE(world.isFixedBase());
  EXPECT_EQ(world.numJoints(), 0u);
  const double dt = world.timeStep();
  for (int k = 0; k < 500; ++k) world.step();
  const double t = world.time();
  const BaseState base = world.baseState();
  // Semi-implicit Euler: z_n = z0 - g t^2/2 - g dt t/2 (see the prismatic test).
  EXPECT_NEAR(base.position.z(), 5.0 - 0.5 * kG * t * t, 0.5 * kG * dt * t + 1e-9);
  EXPECT_NEAR(base.position.x(), 0.3, 1e-12);
  EXPECT_NEAR(base.position.y(), -0.2, 1e-12);
  EXPECT_NEAR(base.linear_velocity.z(), -kG * t, 1e-9);
  EXPECT_TRUE(base.angular_velocity.isZero(1e-12));
  EXPECT_TRUE(world.linkWorldPosition("box").isApprox(base.position, 1e-12));
}

// Drops a floating robot from 1 m onto the ground plane and returns its resting base height.
double restingHeight(const std::string& xml, const std::string& name) {
  WorldSettings settings;
  settings.ground_plane = true;
  settings.initial_base_position = Eigen::Vector3d(0, 0, 1.0);
  BulletWorld world(*parseRobotModel(xml, name), settings);
  // Lands after 0.43 s; a tall box rocks on its small face (friction 1) for a
  // while before it settles.
  for (int k = 0; k < 3000; ++k) world.step();
  EXPECT_LT(world.baseState().linear_velocity.norm(), 0.01) << name;
  return world.baseState().position.z();
}

// Half the cube's side; contacts settle within a few millimetres (solver softness + margins).
constexpr double kCubeHalfSide = 0.1;
constexpr double kContactTolerance = 0.005;

TEST(BulletWorldBody, FloatingBoxLandsOnGroundPlane) {
  EXPECT_NEAR(restingHeight(kFreeBoxUrdf, "box.urdf"), kCubeHalfSide, kContactTolerance);
}

std::string meshBoxUrdf(const std::string& mesh_file) {
  return R"(<robot name="mesh_box"><link name="box"><inertial><mass value="2"/>
    <inertia ixx="0.013333" ixy="0" ixz="0" iyy="0.013333" iyz="0" izz="0.013333"/></inertial>
    <collision><geometry><mesh filename=")" +
         kAssetsDir + "meshes/" + mesh_file + R"("/></geometry></collision></link></robot>)";
}

TEST(BulletWorldBody, BinaryAndAsciiStlCubesLandAsConvexHulls) {
  EXPECT_NEAR(restingHeight(meshBoxUrdf("cube_binary.stl"), "binary.urdf"), kCubeHalfSide, kContactTolerance);
  EXPECT_NEAR(restingHeight(meshBoxUrdf("cube_ascii.stl"), "ascii.urdf"), kCubeHalfSide, kContactTolerance);
}

// A 0.2 x 0.4 x 0.6 m box, in COLLADA written in centimetres and in OBJ: it
// lands on its 0.2 x 0.4 face, its centre 0.3 m up.
TEST(BulletWorldBody, ColladaAndObjBoxesLandAsConvexHulls) {
  EXPECT_NEAR(restingHeight(meshBoxUrdf("box_20x40x60cm_zup.dae"), "dae.urdf"), 0.3, kContactTolerance);
  EXPECT_NEAR(restingHeight(meshBoxUrdf("box_20x40x60cm.obj"), "obj.urdf"), 0.3, kContactTolerance);
  std::string scaled = meshBoxUrdf("box_20x40x60cm.obj");
  scaled.replace(scaled.find(".obj\"/>"), 7, ".obj\" scale=\"1 -1 0.5\"/>");
  EXPECT_NEAR(restingHeight(scaled, "scaled.urdf"), 0.15, kContactTolerance);
}

// The hopper (a 0.2 m cube, a 0.4 m leg on a hip 0.1 m below its centre, a
// foot ball of r = 0.05 m welded to the leg's end). Spawned at z = 0.3 the
// ball's bottom is at 0.3 − 0.1 − 0.4 − 0.05 = −0.25 m; the leg's box ends at −0.2. With the leg swung level (q = pi/2) nothing
// is below the floor: the base's bottom is at 0.2, the leg's side at 0.175,
// the ball's bottom at 0.15.
const std::string kHopperUrdf = kAssetsDir + "features/hopper.urdf";

TEST(BulletWorldBody, DeepestGroundPenetrationOfTheSpawnPoseByHand) {
  WorldSettings settings;
  settings.ground_plane = true;
  settings.initial_base_position = Eigen::Vector3d(0, 0, 0.3);
  BulletWorld world(*loadRobotModelFile(kHopperUrdf), settings);
  GroundPenetration deepest = world.deepestGroundPenetration();
  EXPECT_EQ(deepest.link, "foot");  // the welded link, not the body it is merged into
  EXPECT_NEAR(deepest.depth_m, 0.25, 1e-9);

  world.setJointState(world.jointIndex("hip"), std::numbers::pi / 2, 0.0);
  deepest = world.deepestGroundPenetration();
  EXPECT_EQ(deepest.link, "");
  EXPECT_EQ(deepest.depth_m, 0.0);

  // Turned upside down (roll pi) the leg points up: the cube's bottom is at
  // 0.3 − 0.1 = 0.2; and nothing is below a floor that is not there.
  settings.initial_base_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()));
  EXPECT_EQ(BulletWorld(*loadRobotModelFile(kHopperUrdf), settings).deepestGroundPenetration().link, "");
  settings.initial_base_orientation = Eigen::Quaterniond::Identity();
  settings.ground_plane = false;
  EXPECT_EQ(BulletWorld(*loadRobotModelFile(kHopperUrdf), settings).deepestGroundPenetration().link, "");
}

TEST(BulletWorldBody, MeshPendulumAssetLoads) {
  BulletWorld world(*loadRobotModelFile(kAssetsDir + "mesh_pendulum.urdf"));
  ASSERT_EQ(world.jointNames(), std::vector<std::string>{"hinge"});
  EXPECT_TRUE(world.linkWorldPosition("bob").isApprox(Eigen::Vector3d(0, 0, 2), 1e-12));
}

TEST(BulletWorldBody, MasslessFloatingRootIsRejected) {
  const std::string xml = R"(<robot name="ghost"><link name="base"/></robot>)";
  try {
    BulletWorld world(*parseRobotModel(xml, "ghost.urdf"));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("root link 'base'"), std::string::npos) << e.what();
  }
  WorldSettings fixed;
  fixed.fixed_base = FixedBase::fixed;
  EXPECT_NO_THROW(BulletWorld(*parseRobotModel(xml, "ghost.urdf"), fixed));
}

}  // namespace
}  // namespace servoloop::sim_bullet
