// xacro's Python in ${...} past arithmetic: methods of str, list and dict,
// indexing and slicing, and the builtins real descriptions use (franka's
// ${xyz.split(' ')[0]}), each against what Python 3 prints for the same
// expression, and one clear error per mistake naming the expression.
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "servoloop/description/xacro.hpp"
#include "temp_dir.hpp"
#include "xacro_test_support.hpp"

namespace servoloop::xacro_python_test {
namespace {

using testing::TempDir;
using testing::writeFile;

const char* const kRobotOpen = R"~(<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">)~";

// Properties the expressions below use; format patterns live in properties
// because xacro's ${...} ends at the first '}'.
const char* const kProperties = R"~(
  <xacro:property name="xyz" value="0 0.08 -0.13"/>
  <xacro:property name="name" value="panda_joint1"/>
  <xacro:property name="pattern" value="'{}_link_{:03d}'"/>
  <xacro:property name="numbered" value="'{0}-{1}-{0}'"/>
  <xacro:property name="named" value="'{name}:{v:.3f}'"/>
  <xacro:property name="aligned" value="'{:>6}|{:&lt;4}|{:^5}|'"/>
  <xacro:property name="first" value="${xyz.split(' ')[0]}"/>
  <xacro:property name="cfg" value="${xacro.load_yaml('limits.yaml')}"/>)~";

// joints is written j2 before j1: a dict keeps the order of its file.
const char* const kLimitsYaml =
    "joints:\n  j2: {limit: {lower: -1.5, upper: 1.5}}\n  j1: {limit: {lower: -2.8973, upper: 2.8973}}\n"
    "names: [shoulder, elbow, wrist]\n";

std::string expandBody(const std::string& body) {
  TempDir dir("servoloop-xacro-python");
  writeFile(dir.path() / "limits.yaml", kLimitsYaml);
  writeFile(dir.path() / "r.urdf.xacro", std::string(kRobotOpen) + kProperties + body + "</robot>");
  return expandXacroFile(dir.path() / "r.urdf.xacro");
}

// The text ${expression} expands to, with kProperties defined.
std::string valueOf(const std::string& expression) {
  const std::string out = expandBody(R"~(<v x="${)~" + expression + R"~(}"/>)~");
  const auto start = out.find("<v x=\"") + 6;
  std::string text = out.substr(start, out.find('"', start) - start);
  // tinyxml2 writes the XML escapes of the attribute.
  for (const auto& [escape, plain] : {std::pair<std::string, std::string>{"&apos;", "'"}, {"&lt;", "<"},
                                      {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}}) {
    for (auto at = text.find(escape); at != std::string::npos; at = text.find(escape, at + 1)) {
      text.replace(at, escape.size(), plain);
    }
  }
  return text;
}

std::string errorOfExpression(const std::string& expression) {
  try {
    valueOf(expression);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

::testing::AssertionResult holds(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << part << "' not in: " << text;
}

TEST(XacroPython, StringMethodsGiveWhatPythonGives) {
  // franka_description's utils.xacro: the capsule's position, a coordinate each.
  EXPECT_EQ(valueOf("xyz.split(' ')"), "['0', '0.08', '-0.13']");
  EXPECT_EQ(valueOf("xyz.split(' ')[2]"), "-0.13");
  EXPECT_EQ(valueOf("float(xyz.split()[1]) * 2"), "0.16");
  EXPECT_EQ(valueOf("'  a  b  c  '.split()"), "['a', 'b', 'c']");
  EXPECT_EQ(valueOf("'  a  b  c  '.split(None, 1)"), "['a', 'b  c  ']");
  EXPECT_EQ(valueOf("'a,b,,c'.split(',')"), "['a', 'b', '', 'c']");
  EXPECT_EQ(valueOf("'a,b,c'.split(',', 1)"), "['a', 'b,c']");
  EXPECT_EQ(valueOf("'a,b,c'.rsplit(',', 1)"), "['a,b', 'c']");
  EXPECT_EQ(valueOf("'  a b  '.rsplit(maxsplit=1)"), "['  a', 'b']");
  EXPECT_EQ(valueOf("'_'.join(['l', 'arm', '1'])"), "l_arm_1");
  EXPECT_EQ(valueOf("'-'.join('abc')"), "a-b-c");
  EXPECT_EQ(valueOf("'[' + '  x \\t'.strip() + ']'"), "[x]");
  EXPECT_EQ(valueOf("'xxhixx'.strip('x') + ' ' + 'xxhixx'.lstrip('x') + ' ' + 'xxhixx'.rstrip('x')"), "hi hixx xxhi");
  EXPECT_EQ(valueOf("'left_arm_left'.replace('left', 'right')"), "right_arm_right");
  EXPECT_EQ(valueOf("'left_arm_left'.replace('left', 'right', 1)"), "right_arm_left");
  EXPECT_EQ(valueOf("'ab'.replace('', '-')"), "-a-b-");
  EXPECT_EQ(valueOf("'Panda_Link'.lower() + ' ' + 'Panda_Link'.upper()"), "panda_link PANDA_LINK");
  EXPECT_EQ(valueOf("name.startswith('panda_')"), "True");
  EXPECT_EQ(valueOf("name.endswith('1')"), "True");
  EXPECT_EQ(valueOf("name.startswith('joint', 6)"), "True");
  EXPECT_EQ(valueOf("'abc'.startswith('', 4)"), "False");
  EXPECT_EQ(valueOf("name.find('joint')"), "6");
  EXPECT_EQ(valueOf("name.find('x')"), "-1");
  EXPECT_EQ(valueOf("'abc'.find('', 3)"), "3");
  EXPECT_EQ(valueOf("'abc'.find('', 4)"), "-1");
  EXPECT_EQ(valueOf("'banana'.count('an')"), "2");
  EXPECT_EQ(valueOf("'abc'.count('')"), "4");
  EXPECT_EQ(valueOf("name.split('_')[-1].upper()"), "JOINT1");
}

TEST(XacroPython, FormatFollowsPythonsMiniLanguage) {
  EXPECT_EQ(valueOf("pattern.format('arm', 7)"), "arm_link_007");
  EXPECT_EQ(valueOf("numbered.format('a', 'b')"), "a-b-a");
  EXPECT_EQ(valueOf("named.format(name='x', v=3.14159)"), "x:3.142");
  EXPECT_EQ(valueOf("aligned.format('ab', 1, 'c')"), "    ab|1   |  c  |");
  // Patterns without braces can be written inline.
  EXPECT_EQ(valueOf("'plain'.format(1)"), "plain");
}

TEST(XacroPython, IndexingAndSlicingFollowPython) {
  const std::string s = "'abcdef'";
  EXPECT_EQ(valueOf(s + "[1:-1]"), "bcde");
  EXPECT_EQ(valueOf(s + "[::-1]"), "fedcba");
  EXPECT_EQ(valueOf(s + "[::2]"), "ace");
  EXPECT_EQ(valueOf(s + "[-2:]"), "ef");
  EXPECT_EQ(valueOf("'[' + " + s + "[10:] + ']'"), "[]");  // past the end: empty, not an error
  EXPECT_EQ(valueOf(s + "[:100]"), "abcdef");
  EXPECT_EQ(valueOf(s + "[5:1:-2]"), "fd");
  EXPECT_EQ(valueOf(s + "[-100:2]"), "ab");
  EXPECT_EQ(valueOf(s + "[-1]"), "f");
  EXPECT_EQ(valueOf("[1, 2, 3, 4][1:3]"), "[2, 3]");
  EXPECT_EQ(valueOf("[1, 2, 3, 4][::-1]"), "[4, 3, 2, 1]");
  EXPECT_EQ(valueOf("[1, 2, 3][-1]"), "3");
  EXPECT_EQ(valueOf("[1, 2, 3][True]"), "2");  // a bool is an int
}

TEST(XacroPython, YamlDictsReadByKeyAttributeAndMethodInFileOrder) {
  // franka's ${config[name]['limit']} and ${limits.lower}.
  EXPECT_EQ(valueOf("cfg['joints']['j1']['limit']['upper']"), "2.8973");
  EXPECT_EQ(valueOf("cfg.joints.j1.limit.lower"), "-2.8973");
  EXPECT_EQ(valueOf("cfg.joints[name.split('_')[-1].replace('joint', 'j')].limit.upper"), "2.8973");
  EXPECT_EQ(valueOf("'j1' in cfg.joints"), "True");
  EXPECT_EQ(valueOf("'j3' in cfg.joints"), "False");
  EXPECT_EQ(valueOf("cfg.joints.keys()"), "['j2', 'j1']");
  EXPECT_EQ(valueOf("list(cfg.joints)"), "['j2', 'j1']");
  EXPECT_EQ(valueOf("len(cfg.joints)"), "2");
  EXPECT_EQ(valueOf("cfg.joints.get('j9', 0)"), "0");
  EXPECT_EQ(valueOf("cfg.joints.j2"), "{'limit': {'lower': -1.5, 'upper': 1.5}}");
  EXPECT_EQ(valueOf("cfg.names[-1]"), "wrist");
  EXPECT_EQ(valueOf("cfg.names[:2]"), "['shoulder', 'elbow']");
  EXPECT_EQ(valueOf("cfg.names.index('elbow')"), "1");
}

TEST(XacroPython, BuiltinsGiveWhatPythonGives) {
  EXPECT_EQ(valueOf("str(1.0) + str(True)"), "1.0True");
  EXPECT_EQ(valueOf("int('42') + int(' -7 ')"), "35");
  EXPECT_EQ(valueOf("int('ff', 16)"), "255");
  EXPECT_EQ(valueOf("int(-3.9)"), "-3");
  EXPECT_EQ(valueOf("float('1e-3')"), "0.001");
  EXPECT_EQ(valueOf("float(' inf ')"), "inf");
  EXPECT_EQ(valueOf("len([1, 2])"), "2");
  EXPECT_EQ(valueOf("min('b', 'a')"), "a");
  EXPECT_EQ(valueOf("min('hello')"), "e");
  EXPECT_EQ(valueOf("max([1, 2.5])"), "2.5");
  EXPECT_EQ(valueOf("abs(-2.5)"), "2.5");
  EXPECT_EQ(valueOf("sum([1, 2.5])"), "3.5");
  // round: halves to even on the double's exact value (2.675 is 2.67499999...).
  EXPECT_EQ(valueOf("round(2.675, 2)"), "2.67");
  EXPECT_EQ(valueOf("round(0.125, 2)"), "0.12");
  EXPECT_EQ(valueOf("round(-0.5)"), "0");
  EXPECT_EQ(valueOf("round(1234, -2)"), "1200");
  EXPECT_EQ(valueOf("round(1250, -2)"), "1200");
  EXPECT_EQ(valueOf("round(1350, -2)"), "1400");
  EXPECT_EQ(valueOf("str([1, 'a', 2.5])"), "[1, 'a', 2.5]");
  EXPECT_EQ(valueOf("math.sqrt(4) + python.len('ab') + math.pi * 0"), "4.0");
  // xacro.warning prints and gives '' (franka's utils.xacro calls it in text).
  EXPECT_EQ(valueOf("'[' + xacro.warning('no inertia for', 'link9') + ']'"), "[]");
}

// A property's value is read as xacro reads it: '0' from split() becomes the
// int 0, so franka's ${x + sx} adds numbers; the string itself does not add.
// A chain of comparisons stops at its first false link, as in Python:
// 0 > 1 > 1 / 0 is False there, without the ZeroDivisionError the last link
// would raise; with a true first link the division is evaluated.
TEST(XacroPython, ChainedComparisonsStopAtTheFirstFalseLink) {
  EXPECT_EQ(valueOf("0 > 1 > 1 / 0"), "False");
  EXPECT_EQ(valueOf("1 < 2 < 3"), "True");
  EXPECT_EQ(valueOf("1 < 3 < 2"), "False");
  EXPECT_TRUE(holds(errorOfExpression("1 < 2 < 1 / 0"), "division by zero"));
}

TEST(XacroPython, PropertiesReadTheTextOfAnExpressionAsANumber) {
  EXPECT_EQ(valueOf("first + 1"), "1");
  EXPECT_TRUE(holds(errorOfExpression("xyz.split(' ')[0] + 1"), "unsupported operand types for +: str ('0') and int (1)"));
}

TEST(XacroPython, ErrorsNameTheExpressionAndTheFix) {
  std::string error = errorOfExpression("xyz.split(' ')[3]");
  EXPECT_TRUE(holds(error, "r.urdf.xacro:9: xacro: ${xyz.split(' ')[3]}: xyz.split(' ')[3]: index 3 is out of range: "
                           "xyz.split(' ') is a list of 3 items (['0', '0.08', '-0.13']); valid indices are 0 to 2 "
                           "and -3 to -1"));
  error = errorOfExpression("xyz.spilt(' ')");
  EXPECT_TRUE(holds(error, "xyz.spilt(' '): xyz is a str ('0 0.08 -0.13'), which has no method 'spilt'"));
  EXPECT_TRUE(holds(error, "split, rsplit, join, format"));
  EXPECT_TRUE(holds(errorOfExpression("cfg.joints['j7']"), "cfg.joints['j7']: cfg.joints has no key 'j7' (its keys: j2, j1)"));
  EXPECT_TRUE(holds(errorOfExpression("cfg.joints.j7"), "cfg.joints.j7: cfg.joints has no key 'j7' (its keys: j2, j1)"));
  EXPECT_TRUE(holds(errorOfExpression("'abc'[1.5]"), "str indices must be ints or slices, not a float (1.5)"));
  EXPECT_TRUE(holds(errorOfExpression("'abc'[::0]"), "'abc'[::0]: the slice step cannot be zero"));
  EXPECT_TRUE(holds(errorOfExpression("3[0]"), "3 is an int (3), which cannot be indexed"));
  EXPECT_TRUE(holds(errorOfExpression("'-'.join([1, 2])"), "join() needs str items; item 0 is an int (1); convert it with str()"));
  EXPECT_TRUE(holds(errorOfExpression("int('x1')"), "int() cannot read 'x1' as a base-10 integer"));
  EXPECT_TRUE(holds(errorOfExpression("xyz.split('')"), "xyz.split(''): empty separator"));
  EXPECT_TRUE(holds(errorOfExpression("xyz.upper"), "xyz.upper is a method of a str; call it: xyz.upper(...)"));
  EXPECT_TRUE(holds(errorOfExpression("xyz.x"), "xyz.x: xyz is a str ('0 0.08 -0.13'), which has no attribute 'x'"));
  EXPECT_TRUE(holds(errorOfExpression("nope.split()"), "name 'nope' is not defined"));
  EXPECT_TRUE(holds(errorOfExpression("math.nothing"), "'math.nothing' is not a constant of xacro's math module"));
  EXPECT_TRUE(holds(errorOfExpression("pattern.format('arm')"), "more {} fields than the 1 argument(s) given"));
  EXPECT_TRUE(holds(errorOfExpression("pattern.format(1.5, 2.5)"), "unknown format code 'd' for a float (2.5)"));
  EXPECT_TRUE(holds(errorOfExpression("xyz.split(sep=' ', max=1)"), "has no argument 'max' (its arguments: sep, maxsplit)"));
  EXPECT_TRUE(holds(errorOfExpression("(1)(2)"), "(1)(2): (1) is an int (1), not a function"));
  EXPECT_TRUE(holds(errorOfExpression("xacro.fatal('stop here')"), "xacro.fatal: stop here"));
  EXPECT_TRUE(holds(errorOfExpression("frobnicate(1)"), "unknown function 'frobnicate'"));
  // Text that multiplies is bounded as str * int is.
  EXPECT_TRUE(holds(errorOfExpression("('ab' * 1000).replace('', 'x' * 1000)"), "would make a string over 1048576 bytes"));
  EXPECT_TRUE(holds(errorOfExpression("('x' * 2000).join('y' * 1000)"), "would make a string over 1048576 bytes"));
}

// servoloop's capsule arm uses franka_description's constructs (string
// methods, slicing, format, YAML dicts by key and attribute, `in`, a ** block,
// one transmission per interface); expanded for simulation it is the URDF
// written by hand, and without gazebo:=true it has no inertials, world joint
// or transmissions.
TEST(XacroPython, CapsuleArmMatchesItsHandExpandedUrdf) {
  const std::string assets = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/xacro/";
  const std::string simulated = expandXacroFile(assets + "capsule_arm.urdf.xacro", {{"gazebo", "true"}});
  EXPECT_EQ(testing::canonicalXml(simulated),
            testing::canonicalXml(testing::readFile(assets + "capsule_arm_expanded.urdf")));

  const auto simulated_model = loadRobotModelFile(assets + "capsule_arm.urdf.xacro", {{"gazebo", "true"}});
  ASSERT_NE(simulated_model->getJoint("capsule_joint2"), nullptr);
  EXPECT_EQ(simulated_model->getJoint("capsule_joint2")->limits->lower, -1.5);
  EXPECT_EQ(simulated_model->getJoint("capsule_joint1")->safety->soft_upper_limit, 2.5);
  EXPECT_EQ(simulated_model->getLink("capsule_finger")->inertial->mass, 0.1);

  // Comments are dropped; the tool frame's origin is the default "0 0  0.3" with its spaces made single.
  const std::string plain =
      testing::canonicalXml(expandXacroFile(assets + "capsule_arm.urdf.xacro", {{"arm_id", "left"}}));
  EXPECT_EQ(plain.find("<inertial"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("<transmission"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("world"), std::string::npos) << plain;
  const auto model = parseUrdfWithUrdfdom(plain, "capsule_arm.urdf.xacro", false);
  ASSERT_NE(model->getJoint("left_joint2"), nullptr);
  ASSERT_NE(model->getJoint("left_tcp_joint"), nullptr);
  EXPECT_EQ(model->getJoint("left_tcp_joint")->parent_to_joint_origin_transform.position.z, 0.3);
}

}  // namespace
}  // namespace servoloop::xacro_python_test
