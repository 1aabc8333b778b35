// loadRobotModelFile / parseRobotModel: the seed URDFs load, and every bad
// input is rejected with a message naming the file and the element at fault.
#include "servoloop/description/robot_model.hpp"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "log_capture.hpp"
#include "servoloop/core/errors.hpp"
#include "expect_contains.hpp"

namespace servoloop {
namespace {

// gmock is not linked into this test: a plain substring check with the full
// message in the failure output.
const std::string kSeedDir = std::string(SERVOLOOP_SEED_DIR) + "/";
const std::string kAssetsDir = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/";

// A fixed-base one-link robot; `joint` and `link` are spliced in whole.
std::string robot(const std::string& joint, const std::string& link) {
  return R"(<?xml version="1.0"?><robot name="r"><link name="world"/>)" + joint + link + "</robot>";
}

const std::string kGoodJoint = R"(<joint name="j1" type="revolute"><parent link="world"/><child link="arm"/>
  <origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>)";

std::string armLink(const std::string& inertial) { return R"(<link name="arm">)" + inertial + "</link>"; }

const std::string kGoodInertial = R"(<inertial><origin xyz="0 0 0.5"/><mass value="1"/>
  <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.01"/></inertial>)";

// Parses `xml` as "bad.urdf" and returns the ConfigError message ("" if none).
std::string errorOf(const std::string& xml) {
  try {
    parseRobotModel(xml, "bad.urdf");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RobotModel, SeedUrdfsLoad) {
  const auto seed = loadRobotModelFile(kSeedDir + "minimal_robot_description.urdf");
  ASSERT_TRUE(seed);
  EXPECT_EQ(seed->getName(), "one_DOF_robot");
  EXPECT_EQ(seed->getRoot()->name, "world");
  EXPECT_EQ(seed->getJoint("joint1")->type, urdf::Joint::CONTINUOUS);

  const auto with_control = loadRobotModelFile(kSeedDir + "minimal_robot_description_w_jnt_ctl.urdf");
  const auto joint1 = with_control->getJoint("joint1");
  ASSERT_TRUE(joint1);
  EXPECT_EQ(joint1->type, urdf::Joint::REVOLUTE);
  EXPECT_DOUBLE_EQ(joint1->limits->upper, 2.0);
  EXPECT_DOUBLE_EQ(joint1->limits->effort, 10.0);
  EXPECT_DOUBLE_EQ(joint1->dynamics->damping, 1.0);
}

TEST(RobotModel, GoodInlineRobotParses) {
  const auto model = parseRobotModel(robot(kGoodJoint, armLink(kGoodInertial)), "good.urdf");
  EXPECT_EQ(model->links_.size(), 2u);
}

TEST(RobotModel, MissingFileNamesThePath) {
  try {
    loadRobotModelFile("/nonexistent/robot.urdf");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(e.what(), "/nonexistent/robot.urdf");
    EXPECT_CONTAINS(e.what(), "not found");
  }
}

TEST(RobotModel, NotXml) {
  const std::string message = errorOf("<robot name='r'><link name='a'></robot>");
  EXPECT_CONTAINS(message, "bad.urdf");
  EXPECT_CONTAINS(message, "not valid XML");
}

TEST(RobotModel, RootIsNotRobot) {
  EXPECT_CONTAINS(errorOf("<sdf><model/></sdf>"), "bad.urdf: the root element is <sdf>");
}

TEST(RobotModel, NoLinks) {
  const std::string message = errorOf(R"(<robot name="r"></robot>)");
  EXPECT_CONTAINS(message, "bad.urdf");
  EXPECT_CONTAINS(message, "no <link>");
}

TEST(RobotModel, CycleIsRejected) {
  // a -> b -> c -> a: every link has a parent, there is no root.
  const std::string xml = R"(<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
    <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
    <joint name="ca" type="fixed"><parent link="c"/><child link="a"/></joint></robot>)";
  const std::string message = errorOf(xml);
  EXPECT_CONTAINS(message, "bad.urdf");
  EXPECT_CONTAINS(message, "kinematic cycle");
}

TEST(RobotModel, CycleBesideARootIsRejected) {
  // root r, and b <-> c loop on the side: one root, but b and c are unreachable.
  const std::string xml = R"(<robot name="r"><link name="r"/><link name="b"/><link name="c"/>
    <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
    <joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint></robot>)";
  const std::string message = errorOf(xml);
  EXPECT_CONTAINS(message, "kinematic cycle");
  EXPECT_CONTAINS(message, "'b'");
}

TEST(RobotModel, LinkWithTwoParentsIsRejected) {
  const std::string xml = R"(<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
    <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)";
  const std::string message = errorOf(xml);
  EXPECT_CONTAINS(message, "link 'c' is the child of two joints, 'ac' and 'bc'");
}

TEST(RobotModel, SeveralRootsAreRejected) {
  const std::string message = errorOf(R"(<robot name="r"><link name="a"/><link name="b"/></robot>)");
  EXPECT_CONTAINS(message, "bad.urdf: several root links ('a', 'b')");
}

TEST(RobotModel, UnknownJointTypeNamesTheJoint) {
  std::string joint = kGoodJoint;
  joint.replace(joint.find("revolute"), 8, "hinge");
  const std::string message = errorOf(robot(joint, armLink(kGoodInertial)));
  EXPECT_CONTAINS(message, "bad.urdf: joint 'j1' has unknown type 'hinge'");
}

TEST(RobotModel, JointToUnknownLink) {
  const std::string message = errorOf(robot(kGoodJoint, ""));
  EXPECT_CONTAINS(message, "joint 'j1' refers to link 'arm', which is not defined");
}

TEST(RobotModel, MovingLinkWithoutInertialIsRejected) {
  const std::string message = errorOf(robot(kGoodJoint, armLink("")));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' (moved by joint 'j1') has no <inertial>");
}

TEST(RobotModel, FixedLinkWithoutInertialIsAccepted) {
  std::string joint = kGoodJoint;
  joint.replace(joint.find("revolute"), 8, "fixed");
  EXPECT_NO_THROW(parseRobotModel(robot(joint, armLink("")), "fixed.urdf"));
}

TEST(RobotModel, ZeroMassIsRejected) {
  std::string inertial = kGoodInertial;
  inertial.replace(inertial.find("value=\"1\""), 9, "value=\"0\"");
  const std::string message = errorOf(robot(kGoodJoint, armLink(inertial)));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' (moved by joint 'j1') <inertial><mass> is zero");
}

TEST(RobotModel, NegativeMassIsRejected) {
  std::string inertial = kGoodInertial;
  inertial.replace(inertial.find("value=\"1\""), 9, "value=\"-2\"");
  const std::string message = errorOf(robot(kGoodJoint, armLink(inertial)));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm'");
  EXPECT_CONTAINS(message, "is negative");
}

TEST(RobotModel, NonPositiveDefiniteInertiaIsRejected) {
  // Products of inertia larger than the moments: eigenvalues 0.1 - 0.5 < 0.
  std::string inertial = kGoodInertial;
  inertial.replace(inertial.find("ixy=\"0\""), 7, "ixy=\"0.5\"");
  const std::string message = errorOf(robot(kGoodJoint, armLink(inertial)));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' (moved by joint 'j1') <inertial><inertia> is not positive definite");
}

// A moving link "arm" whose <inertia> is `inertia` (the attributes).
std::string armWithInertia(const std::string& inertia) {
  return robot(kGoodJoint, armLink(R"(<inertial><origin xyz="0 0 0.5"/><mass value="1"/><inertia )" + inertia +
                                   "/></inertial>"));
}

TEST(RobotModel, InertiaBreakingTheTriangleInequalityIsRejected) {
  // Positive definite, but 3 > 1 + 1: izz = ∫(x² + y²) dm cannot exceed
  // ixx + iyy = ∫(x² + y² + 2z²) dm.
  const std::string message =
      errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3")"));
  EXPECT_CONTAINS(message,
                  "bad.urdf: link 'arm' (moved by joint 'j1') <inertial><inertia> breaks the triangle inequality "
                  "(principal moments 1, 1, 3: the largest is more than the sum of the other two, 2)");
  EXPECT_CONTAINS(message, "correct ixx, iyy, izz so that each principal moment is at most the sum of the other two");
}

TEST(RobotModel, TriangleInequalityIsCheckedOnThePrincipalMoments) {
  // The moments (1, 1, 3) above, turned 45° about x: the diagonal (1, 2, 2)
  // alone would pass; the principal moments do not.
  const std::string message =
      errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="2" iyz="-1" izz="2")"));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' (moved by joint 'j1') <inertial><inertia> breaks the triangle "
                           "inequality (principal moments 1, 1, 3");
}

TEST(RobotModel, FlatBodiesAtTheTriangleLimitAreAccepted) {
  // A thin disc about its axis: izz = ixx + iyy exactly.
  EXPECT_EQ(errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="2")")), "");
  // The same disc turned 45° about x (principal moments 1, 1, 2 up to rounding
  // in the eigen-decomposition).
  EXPECT_EQ(errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="1.5" iyz="-0.5" izz="1.5")")), "");
  // Moments rounded in the file: 5e-10 of the largest above the limit, inside
  // the 1e-9 relative tolerance ...
  EXPECT_EQ(errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="2.000000001")")), "");
  // ... but 1e-6 above it is not.
  EXPECT_CONTAINS(errorOf(armWithInertia(R"(ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="2.000002")")),
                  "breaks the triangle inequality");
  // A thin rod along z: two equal moments and a small one.
  EXPECT_EQ(errorOf(armWithInertia(R"(ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="1e-6")")), "");
}

void expectLoads(const std::string& path) {
  try {
    loadRobotModelFile(path);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
  }
}

TEST(RobotModel, EveryUrdfOfTheProjectLoads) {
  // The robots, test assets and examples: each one passes every check
  // (positive mass, positive-definite inertia obeying the triangle inequality, ...).
  int files = 0;
  for (const char* folder : {"robots", "tests", "examples"}) {
    for (const auto& entry :
         std::filesystem::recursive_directory_iterator(std::filesystem::path(SERVOLOOP_SOURCE_DIR) / folder)) {
      if (entry.path().extension() != ".urdf") continue;
      ++files;
      expectLoads(entry.path().string());
    }
  }
  for (const char* seed : {"minimal_robot_description.urdf", "minimal_robot_description_w_jnt_ctl.urdf"}) {
    ++files;
    expectLoads(kSeedDir + seed);
  }
  EXPECT_GE(files, 10);
}

TEST(RobotModel, NanOriginIsRejected) {
  std::string joint = kGoodJoint;
  joint.replace(joint.find("xyz=\"0 0 1\""), 11, "xyz=\"0 nan 1\"");
  const std::string message = errorOf(robot(joint, armLink(kGoodInertial)));
  EXPECT_CONTAINS(message, "bad.urdf: joint 'j1' <origin> attribute xyz=\"0 nan 1\"");
  EXPECT_CONTAINS(message, "not a finite number");
}

TEST(RobotModel, InfiniteInertiaIsRejected) {
  std::string inertial = kGoodInertial;
  inertial.replace(inertial.find("iyy=\"0.1\""), 9, "iyy=\"inf\"");
  const std::string message = errorOf(robot(kGoodJoint, armLink(inertial)));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' <inertial><inertia> attribute iyy=\"inf\"");
}

// What urdfdom takes without a word but no physics means: each one error
// naming the element, the value and what is expected.
TEST(RobotModel, ValuesWithoutPhysicalMeaningAreRejected) {
  struct Case {
    std::string from;
    std::string to;
    std::string error;
  };
  const std::vector<Case> cases = {
      {R"(lower="-1" upper="1")", R"(lower="1" upper="-1")",
       "joint 'j1' <limit>: lower=\"1\" is above upper=\"-1\"; swap them"},
      {R"(effort="5")", R"(effort="-5")", "joint 'j1' <limit> attribute effort=\"-5\": '-5' is out of range; expected a limit >= 0"},
      {R"(velocity="1")", R"(velocity="-0.5")", "joint 'j1' <limit> attribute velocity=\"-0.5\": '-0.5' is out of range"},
      {R"(<axis xyz="0 1 0"/>)", R"(<axis xyz="0 1"/>)", "joint 'j1' <axis> attribute xyz=\"0 1\": 2 numbers where 3 are expected"},
      {R"(<axis xyz="0 1 0"/>)", R"(<axis xyz="0 0 0"/>)", "joint 'j1' <axis> attribute xyz=\"0 0 0\": a zero vector has no direction"},
      {R"(rpy="0 0 0")", R"(rpy="0 0 0 0")", "joint 'j1' <origin> attribute rpy=\"0 0 0 0\": 4 numbers where 3 are expected (roll pitch yaw)"},
      {"</joint>", R"(<dynamics damping="-0.1"/></joint>)",
       "joint 'j1' <dynamics> attribute damping=\"-0.1\": '-0.1' is out of range; expected a coefficient >= 0"},
      {"</joint>", R"(<mimic joint="elbow"/></joint>)", "joint 'j1' <mimic joint=\"elbow\">: no joint 'elbow' in this robot"},
      {"</joint>", R"(<mimic joint="j1"/></joint>)", "joint 'j1' <mimic joint=\"j1\">: a joint cannot follow itself"},
  };
  for (const Case& c : cases) {
    std::string joint = kGoodJoint;
    joint.replace(joint.find(c.from), c.from.size(), c.to);
    EXPECT_CONTAINS(errorOf(robot(joint, armLink(kGoodInertial))), "bad.urdf: " + c.error);
  }
  // A fixed joint's axis means nothing; exporters write 0 0 0 there.
  std::string fixed = kGoodJoint;
  fixed.replace(fixed.find("revolute"), 8, "fixed");
  fixed.replace(fixed.find(R"(<axis xyz="0 1 0"/>)"), 19, R"(<axis xyz="0 0 0"/>)");
  EXPECT_EQ(errorOf(robot(fixed, armLink(kGoodInertial))), "");
  const std::vector<std::pair<std::string, std::string>> geometries = {
      {R"(<box size="0.1 0.2"/>)", "<box> attribute size=\"0.1 0.2\": 2 numbers where 3 are expected (three sizes > 0 (m))"},
      {R"(<box size="0.1 -0.2 0.3"/>)", "<box> attribute size=\"0.1 -0.2 0.3\": '-0.2' is out of range"},
      {R"(<cylinder radius="0" length="1"/>)", "<cylinder> attribute radius=\"0\": '0' is out of range; expected a size > 0"},
      {R"(<sphere radius="-1"/>)", "<sphere> attribute radius=\"-1\": '-1' is out of range"},
  };
  for (const auto& [geometry, error] : geometries) {
    const std::string link = R"(<link name="arm">)" + kGoodInertial + "<collision><geometry>" + geometry +
                             "</geometry></collision></link>";
    EXPECT_CONTAINS(errorOf(robot(kGoodJoint, link)), "bad.urdf: link 'arm' <collision><geometry>" + error);
  }
}

TEST(RobotModel, TextThatIsNotUtf8OrDeclaresEntitiesIsNamed) {
  EXPECT_CONTAINS(errorOf("<robot name=\"r\xFF\"><link name=\"a\"/></robot>"),
                  "bad.urdf: byte 14 (0xFF) is not UTF-8, the encoding URDF is read in; save the file as UTF-8");
  EXPECT_CONTAINS(errorOf("<?xml version=\"1.0\"?>\n<!DOCTYPE r [<!ENTITY x \"y\">]>\n<robot name=\"&x;\"><link name=\"a\"/></robot>"),
                  "bad.urdf: declares XML entities");
}

TEST(RobotModel, NanDampingIsRejected) {
  std::string joint = kGoodJoint;
  joint.replace(joint.find("</joint>"), 8, R"(<dynamics damping="NaN"/></joint>)");
  EXPECT_CONTAINS(errorOf(robot(joint, armLink(kGoodInertial))), "bad.urdf: joint 'j1' <dynamics> attribute damping=\"NaN\"");
}

TEST(RobotModel, MissingMeshFileIsNamed) {
  const std::string link = R"(<link name="arm">)" + kGoodInertial +
                           R"(<collision><geometry><mesh filename="meshes/nothere.stl"/></geometry></collision></link>)";
  const std::string message = errorOf(robot(kGoodJoint, link));
  EXPECT_CONTAINS(message, "bad.urdf: link 'arm' <collision> mesh 'meshes/nothere.stl' not found");
}

TEST(RobotModel, MissingPackageMeshIsNamed) {
  const std::string link = R"(<link name="arm">)" + kGoodInertial +
                           R"(<collision><geometry><mesh filename="package://nopkg/arm.stl"/></geometry></collision></link>)";
  const std::string message = errorOf(robot(kGoodJoint, link));
  EXPECT_CONTAINS(message, "link 'arm' <collision> mesh 'package://nopkg/arm.stl'");
  EXPECT_CONTAINS(message, "ROS package 'nopkg' not found");
  EXPECT_CONTAINS(message, "ROS_PACKAGE_PATH");
}

// Descriptions shipped without their visual meshes (large .dae files left
// out) still load: no backend draws them. One warning names the file.
TEST(RobotModel, MissingVisualMeshIsAWarning) {
  const std::string link = R"(<link name="arm">)" + kGoodInertial +
                           R"(<visual><geometry><mesh filename="package://nopkg/arm.dae"/></geometry></visual></link>)";
  test::LogCapture log;
  EXPECT_EQ(errorOf(robot(kGoodJoint, link)), "");
  EXPECT_EQ(log.count("link 'arm' <visual> mesh 'package://nopkg/arm.dae'"), 1u) << log.text();
  EXPECT_EQ(log.count("ROS package 'nopkg' not found"), 1u) << log.text();
}

// The node and the simulated hardware each parse the description: the
// warning still comes once. (Its own mesh name: the report is per process.)
TEST(RobotModel, AMissingVisualMeshIsReportedOnceForTwoParses) {
  const std::string link = R"(<link name="arm">)" + kGoodInertial +
                           R"(<visual><geometry><mesh filename="package://nopkg/forearm.dae"/></geometry></visual></link>)";
  test::LogCapture log;
  EXPECT_EQ(errorOf(robot(kGoodJoint, link)), "");
  EXPECT_EQ(errorOf(robot(kGoodJoint, link)), "");
  EXPECT_EQ(log.count("<visual> mesh 'package://nopkg/forearm.dae'"), 1u) << log.text();
}

TEST(RobotModel, MeshesResolveRelativeAndPackageUris) {
  const auto model = loadRobotModelFile(kAssetsDir + "mesh_pendulum.urdf");
  const auto bob = model->getLink("bob");
  ASSERT_TRUE(bob);
  const auto* collision_mesh = dynamic_cast<const urdf::Mesh*>(bob->collision_array.at(0)->geometry.get());
  const auto* visual_mesh = dynamic_cast<const urdf::Mesh*>(bob->visual_array.at(0)->geometry.get());
  ASSERT_NE(collision_mesh, nullptr);
  ASSERT_NE(visual_mesh, nullptr);
  namespace fs = std::filesystem;
  EXPECT_TRUE(fs::path(collision_mesh->filename).is_absolute());
  EXPECT_TRUE(fs::equivalent(collision_mesh->filename, kAssetsDir + "meshes/cube_binary.stl"));
  EXPECT_TRUE(fs::equivalent(visual_mesh->filename, kAssetsDir + "meshes/cube_ascii.stl"));
}

}  // namespace
}  // namespace servoloop
