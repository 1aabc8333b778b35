// parseTransmissions on the seed URDFs and on one inline URDF per kind of
// malformed <transmission>; every error must name the file, the transmission
// and the fix.
#include "servoloop/transmissions/transmission_parser.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "log_capture.hpp"
#include "servoloop/core/errors.hpp"

namespace st = servoloop::transmissions;

namespace {

std::string readSeed(const std::string& name) {
  const std::string path = std::string(SERVOLOOP_SEED_DIR) + "/" + name;
  std::ifstream file(path);
  EXPECT_TRUE(file.good()) << "cannot open " << path;
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A three-link robot with two revolute joints, one prismatic and one fixed,
// plus the given transmission elements.
std::string robotWith(const std::string& transmissions) {
  return R"(<?xml version="1.0"?>
<robot name="test_bot">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="l2"/><child link="l3"/>
    <limit effort="1" velocity="1" lower="0" upper="0.5"/></joint>
  <joint name="tool_mount" type="fixed"><parent link="l3"/><child link="tool"/></joint>
)" + transmissions +
         "\n</robot>\n";
}

const char* kSimpleOk = R"(
  <transmission name="t_slide">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="slide"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="slide_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>)";

std::string parseError(const std::string& urdf) {
  try {
    st::parseTransmissions(urdf, "bad_bot.urdf");
  } catch (const servoloop::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError";
  return {};
}

// The message names the file, the transmission and contains every fragment.
void expectProblem(const std::string& message, const std::string& transmission,
                   const std::vector<std::string>& fragments) {
  EXPECT_NE(message.find("bad_bot.urdf: transmission " + transmission + ":"), std::string::npos)
      << message;
  for (const auto& fragment : fragments) {
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "missing '" << fragment << "' in: " << message;
  }
}

}  // namespace

// --- Well-formed descriptions.

TEST(TransmissionParser, SeedRobotWithJointControlHasTran1) {
  const auto infos = st::parseTransmissions(readSeed("minimal_robot_description_w_jnt_ctl.urdf"),
                                            "minimal_robot_description_w_jnt_ctl.urdf");
  ASSERT_EQ(infos.size(), 1u);
  const st::TransmissionInfo& tran1 = infos[0];
  EXPECT_EQ(tran1.name, "tran1");
  EXPECT_EQ(tran1.type, st::kSimpleTransmissionType);
  ASSERT_EQ(tran1.joints.size(), 1u);
  EXPECT_EQ(tran1.joints[0].name, "joint1");
  EXPECT_EQ(tran1.joints[0].hardware_interfaces, std::vector<std::string>{"EffortJointInterface"});
  EXPECT_EQ(tran1.joints[0].offset, 0.0);
  ASSERT_EQ(tran1.actuators.size(), 1u);
  EXPECT_EQ(tran1.actuators[0].name, "motor1");
  EXPECT_EQ(tran1.actuators[0].mechanical_reduction, 1.0);
}

TEST(TransmissionParser, SeedRobotWithoutTransmissionsGivesNone) {
  EXPECT_TRUE(st::parseTransmissions(readSeed("minimal_robot_description.urdf"),
                                     "minimal_robot_description.urdf")
                  .empty());
}

TEST(TransmissionParser, NormalisesPrefixesAndReadsNumbers) {
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="t1">
    <type>SimpleTransmission</type>
    <joint name="j1">
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      <hardwareInterface>VelocityJointInterface</hardwareInterface>
      <offset> -0.25 </offset>
    </joint>
    <actuator name="m1">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>+50</mechanicalReduction>
    </actuator>
  </transmission>)"),
                                            "ok.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].type, st::kSimpleTransmissionType);
  EXPECT_EQ(infos[0].joints[0].hardware_interfaces,
            (std::vector<std::string>{"PositionJointInterface", "VelocityJointInterface"}));
  EXPECT_EQ(infos[0].joints[0].offset, -0.25);
  EXPECT_EQ(infos[0].joints[0].mechanical_reduction, 1.0);  // default
  EXPECT_EQ(infos[0].actuators[0].hardware_interfaces,
            std::vector<std::string>{"EffortJointInterface"});
  EXPECT_EQ(infos[0].actuators[0].mechanical_reduction, 50.0);
}

TEST(TransmissionParser, AcceptsLegacyTypeAttribute) {
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="legacy" type="transmission_interface/SimpleTransmission">
    <joint name="j2"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m2"><mechanicalReduction>3</mechanicalReduction></actuator>
  </transmission>)"),
                                            "legacy.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].type, st::kSimpleTransmissionType);
}

// gazebo_ros_control loads a robot whose transmission type it cannot model;
// so does servoloop: the transmission is skipped with one warning.
TEST(TransmissionParser, SkipsAnUnknownTypeWithOneWarning) {
  servoloop::test::LogCapture log;
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="belt">
    <type>transmission_interface/BeltTransmission</type>
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>2</mechanicalReduction></actuator>
  </transmission>)" + std::string(kSimpleOk)),
                                            "belt.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].name, "t_slide");
  EXPECT_EQ(log.count("unknown type 'transmission_interface/BeltTransmission'"), 1u) << log.text();
  EXPECT_NE(log.text().find("belt.urdf: transmission 'belt'"), std::string::npos) << log.text();
  EXPECT_NE(log.text().find("skipped"), std::string::npos) << log.text();
}

// ros_control ignores an actuator's <hardwareInterface> in the modern form;
// one it does not know at all is a warning naming it, and loads.
TEST(TransmissionParser, UnknownActuatorInterfaceIsOneWarning) {
  servoloop::test::LogCapture log;
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="t1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><hardwareInterface>EffortActuatorInterface</hardwareInterface>
      <hardwareInterface>TorqueMotorInterface</hardwareInterface><mechanicalReduction>2</mechanicalReduction></actuator>
  </transmission>)"),
                                            "act.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(log.count("act.urdf: transmission 't1': actuator 'm1': <hardwareInterface> 'TorqueMotorInterface' is not "
                      "an interface ros_control knows"),
            1u)
      << log.text();
  EXPECT_EQ(log.count("'EffortActuatorInterface' is not"), 0u) << log.text();
}

// pr2_mechanism_model's form (PR2, ros_controllers' diffbot test robot):
// type attribute, reduction on the transmission, no hardware interface.
// Skipped with one warning; other transmissions are still read.
TEST(TransmissionParser, SkipsThePr2MechanismFormWithOneWarning) {
  servoloop::test::LogCapture log;
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="caster_trans" type="SimpleTransmission">
    <actuator name="caster_motor"/>
    <joint name="j1"/>
    <mechanicalReduction>-79.2</mechanicalReduction>
  </transmission>)" + std::string(kSimpleOk)),
                                            "pr2.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].name, "t_slide");
  EXPECT_EQ(log.count("pr2.urdf: transmission 'caster_trans': the pre-ros_control form"), 1u) << log.text();
  EXPECT_NE(log.text().find("<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"),
            std::string::npos);
}

// A PR2 has 30 of them: one warning names the first four and counts the rest
// (one line per transmission buried everything else the launch printed).
TEST(TransmissionParser, ManyTransmissionsOfThePr2MechanismFormShareOneWarning) {
  servoloop::test::LogCapture log;
  std::string transmissions;
  for (int i = 1; i <= 6; ++i) {
    transmissions += "<transmission name=\"c" + std::to_string(i) +
                     "\" type=\"SimpleTransmission\"><actuator name=\"m" + std::to_string(i) +
                     "\"/><joint name=\"j1\"/><mechanicalReduction>2</mechanicalReduction></transmission>";
  }
  const auto infos = st::parseTransmissions(robotWith(transmissions + std::string(kSimpleOk)), "pr2.urdf");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(log.count("the pre-ros_control form"), 1u) << log.text();
  EXPECT_EQ(log.count("pr2.urdf: 6 transmissions 'c1', 'c2', 'c3', 'c4' and 2 more: the pre-ros_control form"), 1u)
      << log.text();
}

// franka_description's form: one SimpleTransmission per hardware interface of
// a joint, all with the same name and actuator and no <mechanicalReduction>,
// which franka_gazebo's plugin (and gazebo_ros_control) accept. They load as
// one transmission offering every interface, reduction 1, with one note each
// for the merge and the missing reductions.
TEST(TransmissionParser, OneTransmissionPerInterfaceMergesIntoOneWithANote) {
  servoloop::test::LogCapture log;
  std::string transmissions;
  for (const char* interface : {"PositionJointInterface", "VelocityJointInterface", "EffortJointInterface"}) {
    for (const char* joint : {"j1", "j2"}) {
      transmissions += std::string("<transmission name=\"") + joint + "_transmission\">" +
                       "<type>transmission_interface/SimpleTransmission</type><joint name=\"" + joint +
                       "\"><hardwareInterface>hardware_interface/" + interface + "</hardwareInterface></joint>" +
                       "<actuator name=\"" + joint + "_motor\"><hardwareInterface>hardware_interface/" + interface +
                       "</hardwareInterface></actuator></transmission>";
    }
  }
  const auto infos = st::parseTransmissions(robotWith(transmissions + std::string(kSimpleOk)), "arm.urdf");
  ASSERT_EQ(infos.size(), 3u);
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string joint = i == 0 ? "j1" : "j2";
    EXPECT_EQ(infos[i].name, joint + "_transmission");
    EXPECT_EQ(infos[i].type, st::kSimpleTransmissionType);
    ASSERT_EQ(infos[i].joints.size(), 1u);
    EXPECT_EQ(infos[i].joints[0].name, joint);
    EXPECT_EQ(infos[i].joints[0].hardware_interfaces,
              (std::vector<std::string>{"PositionJointInterface", "VelocityJointInterface", "EffortJointInterface"}));
    ASSERT_EQ(infos[i].actuators.size(), 1u);
    EXPECT_EQ(infos[i].actuators[0].name, joint + "_motor");
    EXPECT_EQ(infos[i].actuators[0].mechanical_reduction, 1.0);
  }
  EXPECT_EQ(infos[2].name, "t_slide");
  EXPECT_EQ(log.count("arm.urdf: 2 joints have one SimpleTransmission per hardware interface; each joint's are "
                      "merged into one offering all of them"),
            1u)
      << log.text();
  EXPECT_EQ(log.count("j1 (PositionJointInterface, VelocityJointInterface, EffortJointInterface), j2 ("), 1u)
      << log.text();
  EXPECT_EQ(log.count("arm.urdf: actuators j1_motor, j2_motor without <mechanicalReduction> are taken as a direct "
                      "drive (reduction 1)"),
            1u)
      << log.text();
  EXPECT_EQ(log.count("warning"), 0u) << log.text();
}

// A joint's second transmission (another interface) is merged into its
// first, but the actuator it names must not belong to another joint's.
TEST(TransmissionParser, AMergedTransmissionCannotTakeAnotherJointsActuator) {
  const auto simple = [](const char* name, const char* joint, const char* interface, const char* actuator) {
    return std::string("<transmission name=\"") + name + "\"><type>transmission_interface/SimpleTransmission</type>" +
           "<joint name=\"" + joint + "\"><hardwareInterface>hardware_interface/" + interface +
           "</hardwareInterface></joint><actuator name=\"" + actuator +
           "\"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>";
  };
  const std::string message = parseError(robotWith(simple("t1", "j1", "EffortJointInterface", "m1") +
                                                   simple("t2", "j2", "EffortJointInterface", "m2") +
                                                   simple("t1_velocity", "j1", "VelocityJointInterface", "m2")));
  EXPECT_NE(message.find("actuator 'm2' is already used by transmission"), std::string::npos) << message;
  EXPECT_NE(message.find("t2"), std::string::npos) << message;
}

// gazebo_ros_control drives a joint whose actuator has no reduction directly:
// reduction 1, with a note rather than an error.
TEST(TransmissionParser, AnActuatorWithoutReductionIsADirectDriveWithANote) {
  servoloop::test::LogCapture log;
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="tran1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor1"/>
  </transmission>)"),
                                            "direct.urdf");
  ASSERT_EQ(infos.size(), 1u);
  ASSERT_EQ(infos[0].actuators.size(), 1u);
  EXPECT_EQ(infos[0].actuators[0].mechanical_reduction, 1.0);
  EXPECT_EQ(log.count("direct.urdf: actuator motor1 without <mechanicalReduction> is taken as a direct drive "
                      "(reduction 1), as gazebo_ros_control drives it; add <mechanicalReduction> to say otherwise"),
            1u)
      << log.text();
}

// The pre-2015 form (rrbot and other older descriptions): the interface is in
// the <actuator> only; the joint takes it, with a deprecation warning.
TEST(TransmissionParser, TakesTheActuatorInterfacesOfThePre2015Form) {
  servoloop::test::LogCapture log;
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="tran1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"/>
    <actuator name="motor1">
      <hardwareInterface>VelocityJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>)"),
                                            "old.urdf");
  ASSERT_EQ(infos.size(), 1u);
  ASSERT_EQ(infos[0].joints.size(), 1u);
  EXPECT_EQ(infos[0].joints[0].hardware_interfaces, std::vector<std::string>{"VelocityJointInterface"});
  EXPECT_EQ(log.count("deprecated pre-2015 form"), 1u) << log.text();
  EXPECT_NE(log.text().find("joint 'j1'"), std::string::npos) << log.text();
  EXPECT_NE(log.text().find("move <hardwareInterface>"), std::string::npos) << log.text();
}

TEST(TransmissionParser, OrdersTwoJointTransmissionsByRole) {
  const auto infos = st::parseTransmissions(robotWith(R"(
  <transmission name="wrist">
    <type>transmission_interface/DifferentialTransmission</type>
    <actuator name="m_b"><role>actuator2</role><mechanicalReduction>-20</mechanicalReduction></actuator>
    <actuator name="m_a"><role>actuator1</role><mechanicalReduction>10</mechanicalReduction></actuator>
    <joint name="j2"><role>joint2</role><mechanicalReduction>4</mechanicalReduction>
      <offset>4</offset><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <joint name="j1"><role>joint1</role><mechanicalReduction>-2</mechanicalReduction>
      <offset>-2</offset><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
  </transmission>)"),
                                            "wrist.urdf");
  ASSERT_EQ(infos.size(), 1u);
  const auto& wrist = infos[0];
  EXPECT_EQ(wrist.type, st::kDifferentialTransmissionType);
  ASSERT_EQ(wrist.joints.size(), 2u);
  EXPECT_EQ(wrist.joints[0].name, "j1");
  EXPECT_EQ(wrist.joints[0].mechanical_reduction, -2.0);
  EXPECT_EQ(wrist.joints[1].name, "j2");
  EXPECT_EQ(wrist.joints[1].offset, 4.0);
  ASSERT_EQ(wrist.actuators.size(), 2u);
  EXPECT_EQ(wrist.actuators[0].name, "m_a");
  EXPECT_EQ(wrist.actuators[1].name, "m_b");
  EXPECT_EQ(wrist.actuators[1].mechanical_reduction, -20.0);

  // The built transmission reproduces the reference differential case.
  const auto transmission = st::makeTransmission(wrist);
  double a[2] = {3.0, 5.0}, j[2] = {0.0, 0.0};
  st::ActuatorData actuator{{&a[0], &a[1]}, {}, {}};
  st::JointData joint{{&j[0], &j[1]}, {}, {}};
  transmission->actuatorToJointPosition(actuator, joint);
  EXPECT_NEAR(j[0], -2.0125, 1e-12);
  EXPECT_NEAR(j[1], 4.06875, 1e-12);
}

// --- One malformed case each: the element, the transmission its message
// must name, and the fragments (problem and fix) it must contain.

namespace {

constexpr const char* kSimpleType = "transmission_interface/SimpleTransmission";
constexpr const char* kDifferentialType = "transmission_interface/DifferentialTransmission";
constexpr const char* kFourBarType = "transmission_interface/FourBarLinkageTransmission";
constexpr const char* kEffort = "<hardwareInterface>EffortJointInterface</hardwareInterface>";
constexpr const char* kPosition = "<hardwareInterface>PositionJointInterface</hardwareInterface>";

// <transmission name="…"><type>…</type>children</transmission>; no name
// attribute or no <type> where the argument is empty.
std::string transmission(const std::string& name, const std::string& type, const std::string& children) {
  return "\n  <transmission" + (name.empty() ? "" : " name=\"" + name + "\"") + ">" +
         (type.empty() ? "" : "\n    <type>" + type + "</type>") + children + "\n  </transmission>";
}

std::string joint(const std::string& name, const std::string& children = kEffort) {
  return "\n    <joint name=\"" + name + "\">" + children + "</joint>";
}

std::string actuator(const std::string& name, const std::string& children) {
  return "\n    <actuator name=\"" + name + "\">" + children + "</actuator>";
}

std::string role(const std::string& role_name) { return "<role>" + role_name + "</role>"; }

std::string reduction(const std::string& value) { return "<mechanicalReduction>" + value + "</mechanicalReduction>"; }

// Joint j1 with an effort interface driven by actuator m1 at 1:1, the
// children of the smallest well-formed SimpleTransmission.
const std::string kJ1M1 = joint("j1") + actuator("m1", reduction("1"));

struct MalformedCase {
  std::string name;                // the test's name
  std::string transmissions;       // the <transmission> elements of robotWith()
  std::string named_transmission;  // how the message names the faulty one
  std::vector<std::string> fragments;
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.name; }

std::vector<MalformedCase> malformedCases() {
  const std::string roles_ok = joint("j1", role("joint1") + kEffort) + joint("j2", role("joint2") + kEffort);
  const std::string actuators_ok =
      actuator("m1", role("actuator1") + reduction("1")) + actuator("m2", role("actuator2") + reduction("1"));
  return {
      {"MissingType",
       transmission("t1", "", kJ1M1),
       "'t1'",
       {"has no <type>", "add e.g. <type>transmission_interface/SimpleTransmission"}},
      {"SimpleWithTwoJoints",
       transmission("t1", kSimpleType, joint("j1") + joint("j2") + actuator("m1", reduction("1"))),
       "'t1'",
       {"SimpleTransmission needs exactly 1 <joint>, found 2", "use one <transmission> per joint"}},
      {"DifferentialWithOneActuator",
       transmission("wrist", kDifferentialType, roles_ok + actuator("m1", role("actuator1") + reduction("1"))),
       "'wrist'",
       {"DifferentialTransmission needs exactly 2 <actuator>, found 1",
        "list both actuators, with roles actuator1 and actuator2"}},
      {"FourBarJointWithoutRole",
       transmission("linkage", kFourBarType, joint("j1") + joint("j2", role("joint2") + kEffort) + actuators_ok),
       "'linkage'",
       {"joint 'j1' has no <role>", "<role>joint1</role>", "<role>joint2</role>"}},
      {"DifferentialActuatorWithWrongRole",
       transmission("wrist", kDifferentialType,
                    roles_ok + actuator("m1", role("actuator1") + reduction("1")) +
                        actuator("m2", role("motor2") + reduction("1"))),
       "'wrist'",
       {"actuator 'm2' has role 'motor2'", "use actuator1 or actuator2"}},
      {"DifferentialWithDuplicateRole",
       transmission("wrist", kDifferentialType,
                    joint("j1", role("joint1") + kEffort) + joint("j2", role("joint1") + kEffort) + actuators_ok),
       "'wrist'",
       {"both joints have role 'joint1'", "give one joint1 and the other joint2"}},
      {"JointNotInRobot",
       transmission("t1", kSimpleType, joint("elbow") + actuator("m1", reduction("1"))),
       "'t1'",
       {"joint 'elbow' is not a joint of robot 'test_bot'", "fix the name", "j1, j2, slide"}},
      {"FixedJoint",
       transmission("t1", kSimpleType, joint("tool_mount") + actuator("m1", reduction("1"))),
       "'t1'",
       {"joint 'tool_mount' is not a revolute, continuous or prismatic joint",
        "remove the <joint> or change the joint type"}},
      {"NonNumericReduction",
       transmission("t1", kSimpleType, joint("j1") + actuator("m1", reduction("fifty"))),
       "'t1'",
       {"actuator 'm1': <mechanicalReduction> 'fifty' is not a number", "write a finite decimal number"}},
      {"NonNumericOffset",
       transmission("t1", kSimpleType,
                    joint("j1", std::string(kEffort) + "<offset>0.5rad</offset>") + actuator("m1", reduction("1"))),
       "'t1'",
       {"joint 'j1': <offset> '0.5rad' is not a number", "write a finite decimal number"}},
      {"ZeroReduction",
       transmission("t1", kSimpleType, joint("j1") + actuator("m1", reduction("0"))),
       "'t1'",
       {"actuator 'm1': <mechanicalReduction> is 0", "must be non-zero"}},
      {"JointWithoutHardwareInterface",
       transmission("t1", kSimpleType, joint("j1", "") + actuator("m1", reduction("1"))),
       "'t1'",
       {"joint 'j1' has no <hardwareInterface>",
        "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"}},
      {"UnsupportedHardwareInterface",
       transmission("t1", kSimpleType,
                    joint("j1", "<hardwareInterface>hardware_interface/PosVelJointInterface</hardwareInterface>") +
                        actuator("m1", reduction("1"))),
       "'t1'",
       {"<hardwareInterface> 'PosVelJointInterface' is not supported", "use EffortJointInterface"}},
      {"JointInTwoTransmissions",
       transmission("first", kSimpleType, kJ1M1) +
           transmission("second", kSimpleType, joint("j1") + actuator("m2", reduction("1"))),
       "'second'",
       {"joint 'j1' is already driven by transmission 'first' with the same <hardwareInterface> (EffortJointInterface)",
        "remove one of the two, or give this one another interface"}},
      {"OnePerInterfaceWithDifferentReductions",
       transmission("first", kSimpleType, kJ1M1) +
           transmission("second", kSimpleType, joint("j1", kPosition) + actuator("m1", reduction("2"))),
       "'second'",
       {"joint 'j1' is also driven by transmission 'first', with <mechanicalReduction> 1 there and 2 here",
        "give them the same <mechanicalReduction>"}},
      {"OnePerInterfaceWithDifferentOffsets",
       transmission("first", kSimpleType, kJ1M1) +
           transmission("second", kSimpleType,
                        joint("j1", std::string(kPosition) + "<offset>0.5</offset>") + actuator("m1", reduction("1"))),
       "'second'",
       {"with <offset> 0 there and 0.5 here", "give them the same <offset>"}},
      {"JointOfACoupledTransmissionInASimpleOne",
       transmission("wrist", kDifferentialType, roles_ok + actuators_ok) +
           transmission("extra", kSimpleType, joint("j1", kPosition) + actuator("m3", reduction("1"))),
       "'extra'",
       {"joint 'j1' is already driven by transmission 'wrist'",
        "only SimpleTransmissions (one per hardware interface) may share a joint"}},
      {"ActuatorInTwoTransmissions",
       transmission("first", kSimpleType, kJ1M1) + transmission("second", kSimpleType, joint("j2") + actuator("m1", reduction("1"))),
       "'second'",
       {"actuator 'm1' is already used by transmission 'first'", "give each actuator a unique name"}},
      {"NameOfTwoTransmissions",
       transmission("same", kSimpleType, kJ1M1) + transmission("same", kSimpleType, joint("j2") + actuator("m2", reduction("1"))),
       "'same'",
       {"the name is used by more than one <transmission>", "give each a unique name"}},
      {"CoupledJointsWithDifferentCommandInterfaces",
       transmission("wrist", kDifferentialType,
                    joint("j1", role("joint1") + kEffort) +
                        joint("j2", role("joint2") + "<hardwareInterface>PositionJointInterface</hardwareInterface>") +
                        actuators_ok),
       "'wrist'",
       {"name different command interfaces", "give both the same <hardwareInterface>"}},
      {"TransmissionWithoutName",
       std::string(kSimpleOk) + transmission("", kSimpleType, kJ1M1),
       "#2",
       {"has no name attribute", "add name="}},
  };
}

class MalformedTransmission : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedTransmission, MessageNamesTheFileTheTransmissionTheProblemAndTheFix) {
  expectProblem(parseError(robotWith(GetParam().transmissions)), GetParam().named_transmission, GetParam().fragments);
}

INSTANTIATE_TEST_SUITE_P(TransmissionParser, MalformedTransmission, ::testing::ValuesIn(malformedCases()),
                         [](const ::testing::TestParamInfo<MalformedCase>& info) { return info.param.name; });

}  // namespace

TEST(TransmissionParser, ReportsEveryProblemOnItsOwnLine) {
  const std::string message = parseError(robotWith(std::string(kSimpleOk) + R"(
  <transmission name="a">
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <transmission name="b">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j2"/>
    <actuator name="m2"/>
  </transmission>)"));
  expectProblem(message, "'a'", {"has no <type>"});
  expectProblem(message, "'b'", {"joint 'j2' has no <hardwareInterface>"});
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  EXPECT_EQ(message.find("t_slide"), std::string::npos) << message;
}

TEST(TransmissionParser, MalformedXmlNamesTheFile) {
  const std::string message = parseError("<robot name='x'><link name='a'></robot>");
  EXPECT_NE(message.find("bad_bot.urdf: not well-formed XML"), std::string::npos) << message;
}

TEST(TransmissionParser, MakeTransmissionRejectsZeroReductionNamingTheTransmission) {
  st::TransmissionInfo info;
  info.name = "direct";
  info.type = st::kSimpleTransmissionType;
  info.joints.push_back({"j1", {"EffortJointInterface"}, "", 1.0, 0.0});
  info.actuators.push_back({"m1", {}, "", 0.0});
  try {
    st::makeTransmission(info);
    FAIL() << "expected servoloop::ConfigError";
  } catch (const servoloop::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("transmission 'direct'"), std::string::npos) << message;
    EXPECT_NE(message.find("reduction"), std::string::npos) << message;
  }
}
