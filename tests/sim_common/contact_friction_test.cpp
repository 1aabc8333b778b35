// Contact friction from the URDF's <gazebo reference> <mu1>/<mu2>: Gazebo's
// default, the smaller of two differing values, and errors naming the file,
// the reference and the element.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/sim_common/contact_friction.hpp"

namespace servoloop::sim_common {
namespace {

using ::testing::HasSubstr;

std::string robot(const std::string& gazebo) {
  return "<robot name='r'><link name='base'/><link name='wheel'><inertial><mass value='1'/>"
         "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link>"
         "<link name='caster'/>"
         "<joint name='j' type='continuous'><parent link='base'/><child link='wheel'/></joint>"
         "<joint name='f' type='fixed'><parent link='base'/><child link='caster'/></joint>" +
         gazebo + "</robot>";
}

std::map<std::string, double> frictionOf(const std::string& gazebo) {
  const std::string xml = robot(gazebo);
  return urdfLinkFriction(xml, *parseRobotModel(xml, "r.urdf"), "r.urdf");
}

std::string errorOf(const std::string& gazebo) {
  try {
    frictionOf(gazebo);
  } catch (const ConfigError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected servoloop::ConfigError";
  return "";
}

TEST(ContactFriction, LinksWithoutMuHaveGazebosDefault) {
  const auto friction = frictionOf("<gazebo reference='wheel'><material>Gazebo/Red</material></gazebo>");
  EXPECT_TRUE(friction.empty());
  EXPECT_EQ(linkFriction(friction, "wheel"), 1.0);
  EXPECT_EQ(kDefaultContactFriction, 1.0);
}

TEST(ContactFriction, EachLinkGetsItsOwn) {
  const auto friction = frictionOf(
      "<gazebo reference='wheel'><mu1>0.8</mu1><mu2>0.8</mu2></gazebo>"
      "<gazebo reference='caster'><mu1> 0 </mu1><mu2>0.0</mu2></gazebo>");
  EXPECT_EQ(linkFriction(friction, "wheel"), 0.8);
  EXPECT_EQ(linkFriction(friction, "caster"), 0.0);
  EXPECT_EQ(linkFriction(friction, "base"), 1.0);
}

// Gazebo's older form, as PR2's description writes it.
TEST(ContactFriction, TheValueAttributeFormIsRead) {
  const auto friction = frictionOf("<gazebo reference='wheel'><mu1 value='100.0'/><mu2 value=' 50 '/></gazebo>");
  EXPECT_EQ(linkFriction(friction, "wheel"), 50.0);
  EXPECT_TRUE(errorOf("<gazebo reference='wheel'><mu1 value='much'/></gazebo>").find("<mu1> 'much'") !=
              std::string::npos);
}

// Isotropic contacts: the smaller coefficient; one given alone meets the
// other's default (1).
TEST(ContactFriction, DifferingValuesTakeTheSmaller) {
  EXPECT_EQ(linkFriction(frictionOf("<gazebo reference='wheel'><mu1>0.9</mu1><mu2>0.3</mu2></gazebo>"), "wheel"), 0.3);
  EXPECT_EQ(linkFriction(frictionOf("<gazebo reference='wheel'><mu1>2.5</mu1></gazebo>"), "wheel"), 1.0);
  EXPECT_EQ(linkFriction(frictionOf("<gazebo reference='wheel'><mu2>0.4</mu2></gazebo>"), "wheel"), 0.4);
}

TEST(ContactFriction, AReferenceToNoLinkIsIgnored) {
  EXPECT_TRUE(frictionOf("<gazebo reference='j'><mu1>0.5</mu1></gazebo>").empty());
  EXPECT_TRUE(frictionOf("<gazebo><mu1>0.5</mu1></gazebo>").empty());  // the model's block
}

TEST(ContactFriction, BadValuesNameTheFileTheReferenceAndTheElement) {
  for (const std::string value : {"abc", "-0.5", "nan", "inf", "", "0.5 0.5"}) {
    const std::string error = errorOf("<gazebo reference='wheel'><mu2>" + value + "</mu2></gazebo>");
    EXPECT_THAT(error, HasSubstr("r.urdf: <gazebo reference=\"wheel\"> <mu2> '" + value + "'")) << value;
    EXPECT_THAT(error, HasSubstr("finite number >= 0")) << value;
  }
}

TEST(ContactFriction, TextThatIsNotXmlGivesNothing) {
  const std::string xml = robot("");
  EXPECT_TRUE(urdfLinkFriction("not xml", *parseRobotModel(xml, "r.urdf"), "r.urdf").empty());
}

}  // namespace
}  // namespace servoloop::sim_common
