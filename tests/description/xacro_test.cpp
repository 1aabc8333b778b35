// The xacro expander: each construct against a URDF expanded by hand, Python's
// arithmetic and number printing, and one clear error per mistake.
#include "servoloop/description/xacro.hpp"

#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"
#include "temp_dir.hpp"
#include "xacro_test_support.hpp"

namespace servoloop {
namespace {

using testing::canonicalXml;
using testing::TempDir;
using testing::writeFile;

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

const char* const kOpen = R"~(<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">)~";

// Expands `body` inside a xacro <robot> written to a private folder.
std::string expand(const std::string& body, const XacroArgs& args = {}) {
  TempDir dir("servoloop-xacro");
  writeFile(dir.path() / "robot.urdf.xacro", std::string(kOpen) + body + "</robot>");
  return expandXacroFile(dir.path() / "robot.urdf.xacro", args);
}

std::string errorOf(const std::string& body, const XacroArgs& args = {}) {
  try {
    expand(body, args);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The canonical form of a hand-expanded <robot name="r"> body.
std::string urdf(const std::string& body) { return canonicalXml(R"~(<robot name="r">)~" + body + "</robot>"); }

// The text a single ${expression} expands to.
std::string value(const std::string& expression, const std::string& properties = "") {
  const std::string out = expand(properties + R"~(<v x="${)~" + expression + R"~(}"/>)~");
  const auto start = out.find("<v x=\"") + 6;
  return out.substr(start, out.find('"', start) - start);
}

TEST(Xacro, PropertiesAndArithmeticFollowPython) {
  const std::string props = R"~(<xacro:property name="w" value="0.1"/><xacro:property name="h" value="2"/>)~";
  EXPECT_EQ(value("h/2", props), "1.0");            // true division gives a float
  EXPECT_EQ(value("h//3", props), "0");
  EXPECT_EQ(value("-7//2"), "-4");                  // floor division rounds down
  EXPECT_EQ(value("-7%3"), "2");
  EXPECT_EQ(value("2**10"), "1024");
  EXPECT_EQ(value("2**-1"), "0.5");
  EXPECT_EQ(value("-2**2"), "-4");                  // ** binds tighter than unary minus
  EXPECT_EQ(value("1+2*3-4/2"), "5.0");
  EXPECT_EQ(value("(1+2)*3"), "9");
  EXPECT_EQ(value("w*w + h*h", props), "4.01");
  EXPECT_EQ(value("0.1+0.2"), "0.30000000000000004");
  EXPECT_EQ(value("1/3"), "0.3333333333333333");
  EXPECT_EQ(value("1e-5"), "1e-05");
  EXPECT_EQ(value("1e16"), "1e+16");
  EXPECT_EQ(value("123456789.0*10"), "1234567890.0");
  EXPECT_EQ(value("0.0001"), "0.0001");
  EXPECT_EQ(value("'a' + 'b'"), "ab");
  EXPECT_EQ(value("1 < 2 < 3"), "True");
  EXPECT_EQ(value("1 < 3 < 2"), "False");
  EXPECT_EQ(value("not 1 == 1.0"), "False");
  EXPECT_EQ(value("0 or 'x'"), "x");
  EXPECT_EQ(value("1 and 0"), "0");
  EXPECT_EQ(value("'left' if h > 1 else 'right'", props), "left");
  EXPECT_EQ(value("2 in [1, 2]"), "True");
  EXPECT_EQ(value("'b' not in 'abc'"), "False");
  EXPECT_EQ(value("[1, 2.5, 'x'][-1]"), "x");
  EXPECT_EQ(value("undefined_name if False else 3"), "3");  // the skipped side is not evaluated
}

// Python's integers are unbounded; past 64 bits servoloop gives the float
// of the same value rather than overflowing (the fuzzer found 3 ** 124 as
// undefined behaviour), and a power costs the bits of its exponent.
TEST(Xacro, IntegersBeyondSixtyFourBitsBecomeFloatsOfTheSameValue) {
  EXPECT_EQ(value("2 ** 62"), "4611686018427387904");
  EXPECT_EQ(value("-(2 ** 62) * 2"), "-9223372036854775808");
  EXPECT_NEAR(std::stod(value("3 ** 124")) / std::pow(3.0, 124.0), 1.0, 1e-12);
  EXPECT_NEAR(std::stod(value("9223372036854775807 + 1")), 9223372036854775808.0, 1.0);
  EXPECT_NEAR(std::stod(value("(-9223372036854775807 - 1) - 1")), -9223372036854775809.0, 2048.0);
  EXPECT_NEAR(std::stod(value("4052555153018976267 * 3")), 12157665459056928801.0, 4096.0);
  EXPECT_NEAR(std::stod(value("(-9223372036854775807 - 1) // -1")), 9223372036854775808.0, 1.0);
  EXPECT_NEAR(std::stod(value("-(-9223372036854775807 - 1)")), 9223372036854775808.0, 1.0);
  EXPECT_EQ(value("2 ** 1000000000000"), "inf");
  EXPECT_EQ(value("1 ** 1000000000000000000"), "1");
}

TEST(Xacro, AStringRepeatedPastOneMebibyteIsAnError) {
  EXPECT_EQ(value("'ab' * 3"), "ababab");
  const std::string error = errorOf(R"~(<v x="${'ab' * 10**7}"/>)~");
  EXPECT_CONTAINS(error, "1048576 bytes");
}

TEST(Xacro, MathFunctionsAndConstants) {
  EXPECT_DOUBLE_EQ(std::stod(value("pi")), M_PI);
  EXPECT_DOUBLE_EQ(std::stod(value("radians(90)")), M_PI / 2);
  EXPECT_DOUBLE_EQ(std::stod(value("degrees(pi)")), 180.0);
  EXPECT_DOUBLE_EQ(std::stod(value("math.sin(pi/6)")), std::sin(M_PI / 6));
  EXPECT_DOUBLE_EQ(std::stod(value("cos(0.3)")), std::cos(0.3));
  EXPECT_DOUBLE_EQ(std::stod(value("atan2(1, -1)")), std::atan2(1.0, -1.0));
  EXPECT_DOUBLE_EQ(std::stod(value("sqrt(2)")), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(std::stod(value("pow(2, 0.5)")), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(std::stod(value("exp(1)")), M_E);
  EXPECT_EQ(value("floor(-1.5)"), "-2");
  EXPECT_EQ(value("ceil(1.2)"), "2");
  EXPECT_EQ(value("abs(-3)"), "3");
  EXPECT_EQ(value("round(2.5)"), "2");  // halves to even, as Python
  EXPECT_EQ(value("int(3.9)"), "3");
  EXPECT_EQ(value("float(3)"), "3.0");
  EXPECT_EQ(value("max(1, 4, 2)"), "4");
  EXPECT_EQ(value("min([3, 1.5])"), "1.5");
  EXPECT_EQ(value("str(2) + 'x'"), "2x");
  EXPECT_EQ(value("len('abc')"), "3");
}

TEST(Xacro, PropertyTextIsReadAsANumberOrBooleanAndEvaluatedOnUse) {
  // b uses a, defined after it: properties are evaluated when first used.
  const std::string out = expand(R"~(
    <xacro:property name="b" value="${a * 2}"/>
    <xacro:property name="a" value="1.5"/>
    <xacro:property name="flag" value="true"/>
    <xacro:property name="quoted" value="'007'"/>
    <xacro:property name="under" value="1_000"/>
    <xacro:property name="a" default="99"/>
    <xacro:property name="c" default="4"/>
    <link name="l" b="${b}" flag="${flag}" q="${quoted}" u="${under}" a="${a}" c="${c}" both="${a}${c}"/>)~");
  EXPECT_EQ(canonicalXml(out),
            urdf(R"~(<link name="l" b="3.0" flag="True" q="007" u="1_000" a="1.5" c="4" both="1.54"/>)~"));
}

TEST(Xacro, PropertyBlocksInsertTheirBody) {
  const std::string out = expand(R"~(
    <xacro:property name="shape"><geometry><box size="${s} ${s} ${s}"/></geometry></xacro:property>
    <xacro:property name="s" value="0.5"/>
    <link name="l"><visual><xacro:insert_block name="shape"/></visual></link>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(<link name="l"><visual><geometry><box size="0.5 0.5 0.5"/></geometry></visual></link>)~"));
}

TEST(Xacro, ArgumentsTakeDefaultsAndCommandLineValues) {
  const std::string body = R"~(
    <xacro:arg name="prefix" default="left_"/>
    <xacro:arg name="mass" default="2"/>
    <xacro:arg name="with_tool" default="false"/>
    <link name="$(arg prefix)arm" m="${$(arg mass) * 2}"/>
    <xacro:if value="$(arg with_tool)"><link name="$(arg prefix)tool"/></xacro:if>)~";
  EXPECT_EQ(canonicalXml(expand(body)), urdf(R"~(<link name="left_arm" m="4"/>)~"));
  EXPECT_EQ(canonicalXml(expand(body, {{"prefix", "right_"}, {"with_tool", "true"}, {"mass", "0.5"}})),
            urdf(R"~(<link name="right_arm" m="1.0"/><link name="right_tool"/>)~"));
}

TEST(Xacro, ConditionsAcceptPythonTruthValuesOnly) {
  const std::string out = expand(R"~(
    <xacro:property name="n" value="3"/>
    <xacro:if value="${n > 2}"><a/></xacro:if>
    <xacro:unless value="${n > 2}"><b/></xacro:unless>
    <xacro:if value="1"><c/></xacro:if>
    <xacro:if value="False"><d/></xacro:if>
    <xacro:unless value="0"><e/></xacro:unless>)~");
  EXPECT_EQ(canonicalXml(out), urdf("<a/><c/><e/>"));
  EXPECT_CONTAINS(errorOf(R"~(<xacro:if value="maybe"><a/></xacro:if>)~"), "is \"maybe\", which is not a boolean");
}

TEST(Xacro, MacrosWithDefaultsBlocksAndForwarding) {
  const std::string out = expand(R"~(
    <xacro:property name="radius" value="0.1"/>
    <xacro:macro name="wheel" params="name side:=1 radius:=^ mass:=^|0.5 *origin **extras">
      <link name="${name}_link" r="${radius}" m="${mass}"><xacro:insert_block name="extras"/></link>
      <joint name="${name}_joint" type="continuous" y="${side * 0.2}">
        <xacro:insert_block name="origin"/>
      </joint>
    </xacro:macro>
    <xacro:wheel name="left">
      <origin xyz="0 ${radius} 0"/>
      <extras><mu>0.9</mu><kp>1e5</kp></extras>
    </xacro:wheel>
    <xacro:wheel name="right" side="-1" radius="0.2">
      <origin xyz="0 -0.1 0"/>
      <extras/>
    </xacro:wheel>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(
    <link name="left_link" r="0.1" m="0.5"><mu>0.9</mu><kp>100000</kp></link>
    <joint name="left_joint" type="continuous" y="0.2"><origin xyz="0 0.1 0"/></joint>
    <link name="right_link" r="0.2" m="0.5"></link>
    <joint name="right_joint" type="continuous" y="-0.2"><origin xyz="0 -0.1 0"/></joint>)~"));
}

TEST(Xacro, NestedAndRecursiveMacrosSeeTheCallersProperties) {
  // A chain built by a macro calling itself; `len` comes from where the
  // outermost macro is called (xacro's scopes are dynamic).
  const std::string out = expand(R"~(
    <xacro:property name="len" value="0.25"/>
    <xacro:macro name="chain" params="n parent">
      <xacro:macro name="segment" params="i"><link name="seg${i}" l="${len * i}"/></xacro:macro>
      <xacro:segment i="${n}"/>
      <joint name="j${n}" type="revolute"><parent link="${parent}"/><child link="seg${n}"/></joint>
      <xacro:if value="${n > 1}"><xacro:chain n="${n - 1}" parent="seg${n}"/></xacro:if>
    </xacro:macro>
    <xacro:chain n="3" parent="base"/>
    <xacro:call macro="chain" n="1" parent="top"/>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(
    <link name="seg3" l="0.75"/><joint name="j3" type="revolute"><parent link="base"/><child link="seg3"/></joint>
    <link name="seg2" l="0.5"/><joint name="j2" type="revolute"><parent link="seg3"/><child link="seg2"/></joint>
    <link name="seg1" l="0.25"/><joint name="j1" type="revolute"><parent link="seg2"/><child link="seg1"/></joint>
    <link name="seg1" l="0.25"/><joint name="j1" type="revolute"><parent link="top"/><child link="seg1"/></joint>)~"));
}

TEST(Xacro, MacroLocalPropertiesStayLocalUnlessScopedToTheParent) {
  const std::string out = expand(R"~(
    <xacro:property name="p" value="outer"/>
    <xacro:macro name="m" params="">
      <xacro:property name="p" value="inner"/>
      <xacro:property name="q" value="${p}_q" scope="parent"/>
      <in p="${p}"/>
    </xacro:macro>
    <xacro:m/>
    <out p="${p}" q="${q}"/>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(<in p="inner"/><out p="outer" q="inner_q"/>)~"));
}

TEST(Xacro, ElementAndAttributeBuildNamesFromExpressions) {
  const std::string out = expand(R"~(
    <xacro:property name="kind" value="box"/>
    <geometry><xacro:element xacro:name="${kind}" size="1 2 3"><xacro:attribute name="tag" value="${kind}_1"/></xacro:element></geometry>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(<geometry><box size="1 2 3" tag="box_1"/></geometry>)~"));
}

TEST(Xacro, EscapesEnvironmentAndEval) {
  setenv("SERVOLOOP_XACRO_TEST", "from_env", 1);
  unsetenv("SERVOLOOP_XACRO_UNSET");
  const std::string out = expand(R"~(
    <xacro:arg name="n" default="4"/>
    <a x="$${not_expr}" y="$$(arg n)" e="$(env SERVOLOOP_XACRO_TEST)" o="$(optenv SERVOLOOP_XACRO_UNSET fallback)"
       v="$(eval n * 2)" d="$$5"/>)~");
  EXPECT_EQ(canonicalXml(out), urdf(R"~(<a x="${not_expr}" y="$(arg n)" e="from_env" o="fallback" v="8" d="$$5"/>)~"));
}

TEST(Xacro, OtherPrefixesBoundToTheXacroNamespace) {
  TempDir dir("servoloop-xacro");
  writeFile(dir.path() / "r.xacro", R"~(<robot name="r" xmlns:x="http://ros.org/wiki/xacro">
      <x:property name="a" value="2"/><x:macro name="m" params="v"><l v="${v}"/></x:macro><x:m v="${a}"/></robot>)~");
  EXPECT_EQ(canonicalXml(expandXacroFile(dir.path() / "r.xacro")), urdf(R"~(<l v="2"/>)~"));
}

TEST(Xacro, IncludesRelativeByPackageAndIntoANamespace) {
  TempDir dir("servoloop-xacro");
  // A package whose folder name differs from its package.xml name.
  writeFile(dir.path() / "src/arm_desc_folder/package.xml", "<package><name>arm_description</name></package>");
  writeFile(dir.path() / "src/arm_desc_folder/urdf/arm.xacro", R"~(<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:property name="reach" value="0.8"/>
      <xacro:include filename="parts/hand.xacro"/>
      <xacro:macro name="arm" params="prefix"><link name="${prefix}arm" reach="${reach}"/><xacro:hand prefix="${prefix}"/></xacro:macro>
    </robot>)~");
  writeFile(dir.path() / "src/arm_desc_folder/urdf/parts/hand.xacro", R"~(<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="hand" params="prefix"><link name="${prefix}hand" dir="$(dirname)"/></xacro:macro></robot>)~");
  writeFile(dir.path() / "robot/robot.xacro", std::string(kOpen) + R"~(
      <xacro:include filename="$(find arm_description)/urdf/arm.xacro"/>
      <xacro:include filename="$(find arm_description)/urdf/arm.xacro" ns="second"/>
      <xacro:arm prefix="a_"/>
      <xacro:second.arm prefix="b_"/>
      <l r="${second.reach}"/></robot>)~");
  setenv("ROS_PACKAGE_PATH", (dir.path() / "src").c_str(), 1);
  const std::string out = expandXacroFile(dir.path() / "robot/robot.xacro");
  unsetenv("ROS_PACKAGE_PATH");
  const std::string hand_dir = (dir.path() / "src/arm_desc_folder/urdf/parts").string();
  EXPECT_EQ(canonicalXml(out), urdf(R"~(<link name="a_arm" reach="0.8"/><link name="a_hand" dir=")~" + hand_dir +
                                    R"~("/><link name="b_arm" reach="0.8"/><link name="b_hand" dir=")~" + hand_dir +
                                    R"~("/><l r="0.8"/>)~"));
}

TEST(Xacro, LoadYamlGivesDictsAndLists) {
  TempDir dir("servoloop-xacro");
  writeFile(dir.path() / "limits.yaml", "joints:\n  shoulder: {max: 3.14, effort: 150}\nlist: [1, 2, 3]\nname: ur\n");
  writeFile(dir.path() / "r.xacro", std::string(kOpen) + R"~(
      <xacro:property name="cfg" value="${xacro.load_yaml('limits.yaml')}"/>
      <l max="${cfg['joints']['shoulder']['max']}" e="${cfg.joints.shoulder.effort * 2}" n="${len(cfg['list'])}"
         s="${cfg.name}"/></robot>)~");
  EXPECT_EQ(canonicalXml(expandXacroFile(dir.path() / "r.xacro")), urdf(R"~(<l max="3.14" e="300" n="3" s="ur"/>)~"));
}

TEST(Xacro, ErrorsNameTheFileLineAndWhatIsWrong) {
  EXPECT_CONTAINS(errorOf(R"~(<l x="${nope * 2}"/>)~"), "robot.urdf.xacro:1: xacro: ${nope * 2}: name 'nope' is not defined");
  EXPECT_CONTAINS(errorOf("\n<xacro:wheel/>"), "robot.urdf.xacro:2: xacro: <xacro:wheel>: no macro named 'wheel'");
  const std::string macro = R"~(<xacro:macro name="m" params="a b:=1"><l a="${a}" c="${a / 0}"/></xacro:macro>)~";
  EXPECT_CONTAINS(errorOf(macro + "<xacro:m/>"), "macro 'm' is called without its parameter 'a'");
  EXPECT_CONTAINS(errorOf(macro + R"~(<xacro:m a="1" z="2"/>)~"), "macro 'm' has no parameter 'z' (its parameters: a, b)");
  const std::string inside = errorOf(macro + "\n\n<xacro:m a=\"1\"/>");
  EXPECT_CONTAINS(inside, "division by zero");
  EXPECT_CONTAINS(inside, "in macro 'm' called at");
  EXPECT_CONTAINS(inside, "robot.urdf.xacro:3");
  EXPECT_CONTAINS(errorOf(R"~(<l x="${1 + "/>)~"), "'${' without a closing '}'");
  EXPECT_CONTAINS(errorOf(R"~(<l x="$(arg missing)"/>)~"), "$(arg missing) is not set: pass missing:=value");
  EXPECT_CONTAINS(errorOf(R"~(<xacro:include filename="no_such.xacro"/>)~"), "no_such.xacro not found");
  EXPECT_CONTAINS(errorOf(R"~(<xacro:macro name="loop" params=""><xacro:loop/></xacro:macro><xacro:loop/>)~"),
                  "macro calls nest more than 100 deep");
  EXPECT_CONTAINS(errorOf(R"~(<xacro:property name="p" value="${p}"/><l x="${p}"/>)~"), "defined in terms of itself");
  EXPECT_CONTAINS(errorOf(R"~(<l x="${'a' * 'b'}"/>)~"), "unsupported operand types for *: str");
  EXPECT_CONTAINS(errorOf(R"~(<l x="$(find no_such_package_xyz)/a"/>)~"), "ROS package 'no_such_package_xyz' not found");
  EXPECT_CONTAINS(errorOf("<l>"), "xacro: not well-formed XML");
  // Found by fuzzing: 600 nested brackets overflowed the parser's stack.
  EXPECT_CONTAINS(errorOf("<l x=\"${" + std::string(600, '[') + "}\"/>"),
                  "the expression nests more than 100 levels of brackets, parentheses or operators");
  EXPECT_CONTAINS(errorOf("<l x=\"${" + std::string(600, '-') + "1}\"/>"), "nests more than 100 levels");
  EXPECT_EQ(value(std::string(50, '(') + "1" + std::string(50, ')')), "1");
  // Exponential expansion is cut off instead of filling the memory.
  std::string bomb = R"~(<xacro:macro name="m0" params=""><a/></xacro:macro>)~";
  for (int i = 1; i <= 24; ++i) {
    const std::string prev = "m" + std::to_string(i - 1);
    bomb += "<xacro:macro name=\"m" + std::to_string(i) + "\" params=\"\"><xacro:" + prev + "/><xacro:" + prev +
            "/></xacro:macro>";
  }
  EXPECT_CONTAINS(errorOf(bomb + "<xacro:m24/>"), "the expansion passed 2000000 XML nodes");
}

// `unit` written `times` times over.
std::string repeated(const std::string& unit, int times) {
  std::string out;
  out.reserve(unit.size() * static_cast<std::size_t>(times));
  for (int i = 0; i < times; ++i) out += unit;
  return out;
}

// Found by an issue: chains the parser recursed through without counting them
// (100,000 right-associative ** operators; 20,000 properties each defined
// through the one before) overflowed the stack. Every way the expander
// recurses is bounded, and each refusal is one error naming the file, what
// nests and the limit.
TEST(Xacro, EveryKindOfNestingStopsAtItsLimitWithOneError) {
  // In one expression: 100,000 ** (the issue), unary minus signs and
  // parentheses, and 10,000 of each other kind of nesting.
  const std::string power = errorOf("<l x=\"${1" + repeated("**1", 100000) + "}\"/>");
  EXPECT_CONTAINS(power, "robot.urdf.xacro:1: xacro: ${1**1**1");
  EXPECT_CONTAINS(power, "the expression nests more than 100 levels of brackets, parentheses or operators");
  EXPECT_LT(power.size(), 1000u) << "the expression is shortened in the message";
  const int k = 10000;
  for (const std::string& deep :
       {repeated("- ", 100000) + "1", repeated("(", 100000) + "1" + repeated(")", 100000), repeated("+", k) + "1",
        repeated("not ", k) + "1", repeated("[", k) + repeated("]", k), repeated("{1: ", k) + "1" + repeated("}", k),
        repeated("abs(", k) + "1" + repeated(")", k), repeated("1 if 1 else ", k) + "1",
        repeated("0 if 0 else ", k) + "1", "[0]" + repeated("[0", k) + repeated("]", k), "2" + repeated("**-2", k)}) {
    const std::string error = errorOf("<l x=\"${" + deep + "}\"/>");
    EXPECT_CONTAINS(error, "robot.urdf.xacro:1: xacro: ${");
    EXPECT_CONTAINS(error, "nests more than 100 levels");
  }
  // 100 levels still evaluate: the top of the expression and 99 operators.
  EXPECT_EQ(value("2" + repeated("**1", 99)), "2");
  EXPECT_CONTAINS(errorOf("<l x=\"${2" + repeated("**1", 100) + "}\"/>"), "nests more than 100 levels");
  EXPECT_EQ(value(repeated("-", 99) + "1"), "-1");

  // 20,000 properties, each defined through the one before.
  std::string chain = R"~(<xacro:property name="p0" value="0"/>)~";
  std::string eager = chain;
  for (int i = 1; i <= 20000; ++i) {
    const std::string link = "<xacro:property name=\"p" + std::to_string(i) + "\" value=\"${p" + std::to_string(i - 1) + " + 1}\"";
    chain += link + "/>";
    eager += link + " lazy_eval=\"false\"/>";
  }
  const std::string deep_chain = errorOf(chain + "\n<l x=\"${p20000}\"/>");
  EXPECT_CONTAINS(deep_chain, "robot.urdf.xacro:2: xacro: property 'p20000' is defined through a chain of more than 100 "
                              "properties (p20000 -> p19999 -> p19998 -> ... -> p19901 -> p19900); xacro-file property "
                              "chains deeper than 100 are refused: evaluate properties where they are defined "
                              "(lazy_eval=\"false\")");
  EXPECT_LT(deep_chain.size(), 1000u) << "one error, not one per link";
  EXPECT_EQ(value("p99", chain), "99");  // 100 properties: p99 through p0
  EXPECT_CONTAINS(errorOf(chain + "<l x=\"${p100}\"/>"), "chain of more than 100 properties");
  EXPECT_EQ(value("p20000", eager), "20000");  // evaluated where defined: no chain

  // A value wrapped property by property nests no deeper than 100 levels;
  // one doubled property by property stops at 16 MiB of text (the billion
  // laughs of YAML, in properties).
  std::string wrapped = R"~(<xacro:property name="w0" value="0"/>)~";
  std::string doubled = wrapped;
  std::string text = R"~(<xacro:property name="t0" value="x"/>)~";
  for (int i = 1; i <= 200; ++i) {
    const std::string n = std::to_string(i);
    const std::string before = std::to_string(i - 1);
    wrapped += "<xacro:property name=\"w" + n + "\" value=\"${[w" + before + "]}\" lazy_eval=\"false\"/>";
    doubled += "<xacro:property name=\"w" + n + "\" value=\"${[w" + before + ", w" + before + "]}\" lazy_eval=\"false\"/>";
    text += "<xacro:property name=\"t" + n + "\" value=\"${t" + before + "}${t" + before + "}\" lazy_eval=\"false\"/>";
  }
  EXPECT_CONTAINS(errorOf(wrapped), "${[w100]}: a list nested more than 100 levels deep");
  EXPECT_CONTAINS(errorOf(doubled), "a list whose text would pass 16 MiB");
  EXPECT_CONTAINS(errorOf(text), "would make a text over 16 MiB");
  EXPECT_CONTAINS(errorOf("<xacro:property name=\"s\" value=\"${'x' * 1000000}\"/><l x=\"${s + s}\"/>"),
                  "would make a string over 1048576 bytes");

  // $(...) inside $(...), 100,000 deep.
  EXPECT_CONTAINS(errorOf("<l x=\"" + repeated("$(arg ", 100000) + "x" + repeated(")", 100000) + "\"/>"),
                  "$(...) substitutions nest more than 20 deep");

  // Elements inside elements, across 100 nested macro calls: the limit of
  // all nesting together (each call here is six levels).
  const std::string macro = R"~(<xacro:macro name="w" params="n"><a><b><c><d><xacro:if value="${n > 0}">
      <xacro:w n="${n - 1}"/></xacro:if></d></c></b></a></xacro:macro>)~";
  const std::string elements = errorOf(macro + R"~(<xacro:w n="99"/>)~");
  EXPECT_CONTAINS(elements, "robot.urdf.xacro:");
  EXPECT_CONTAINS(elements, "xacro nests more than 400 levels deep");
  EXPECT_EQ(canonicalXml(expand(macro + R"~(<xacro:w n="1"/>)~")),
            urdf("<a><b><c><d><a><b><c><d></d></c></b></a></d></c></b></a>"));
  // A block passed on by a macro to itself, wrapped in five elements each time.
  const std::string wrap = R"~(<xacro:macro name="m" params="n *b"><xacro:if value="${n > 0}"><xacro:m n="${n - 1}">
      <w><w><w><w><w><xacro:insert_block name="b"/></w></w></w></w></w></xacro:m></xacro:if>
      <xacro:unless value="${n > 0}"><xacro:insert_block name="b"/></xacro:unless></xacro:macro>)~";
  EXPECT_CONTAINS(errorOf(wrap + R"~(<xacro:m n="99"><x/></xacro:m>)~"),
                  "<xacro:insert_block name=\"b\"> would nest the output more than 400 elements deep");
  EXPECT_EQ(canonicalXml(expand(wrap + R"~(<xacro:m n="1"><x/></xacro:m>)~")), urdf("<w><w><w><w><w><x/></w></w></w></w></w>"));

  // A namespace that holds itself, named 100,000 times over.
  TempDir dir("servoloop-xacro");
  writeFile(dir.path() / "ns.xacro", R"~(<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:property name="v" value="1"/></robot>)~");
  writeFile(dir.path() / "r.xacro", std::string(kOpen) + R"~(<xacro:include filename="ns.xacro" ns="a"/><l x="${)~" +
                                        repeated("a.", 100000) + R"~(v}"/></robot>)~");
  std::string namespaced;
  try {
    expandXacroFile(dir.path() / "r.xacro");
  } catch (const ConfigError& e) {
    namespaced = e.what();
  }
  EXPECT_CONTAINS(namespaced, "r.xacro:1: xacro: ");
  EXPECT_LT(namespaced.size(), 1000u);
  writeFile(dir.path() / "m.xacro", std::string(kOpen) + R"~(<xacro:include filename="ns.xacro" ns="a"/><xacro:)~" +
                                        repeated("a.", 100000) + "m/></robot>");
  std::string macro_call;
  try {
    expandXacroFile(dir.path() / "m.xacro");
  } catch (const ConfigError& e) {
    macro_call = e.what();
  }
  EXPECT_CONTAINS(macro_call, "m.xacro:1: xacro: ");
  EXPECT_CONTAINS(macro_call, "no macro named 'a.a.a.");
  EXPECT_LT(macro_call.size(), 1000u);

  // Nothing of the refused expansions stays counted.
  EXPECT_EQ(value(std::string(99, '(') + "1" + std::string(99, ')')), "1");
}

// load_yaml refuses, with one error naming the YAML file and the xacro file,
// what is not a YAML file a robot would have: an alias bomb (the cap of
// parameter files), binary junk, invalid UTF-8, broken YAML, nesting deeper
// than xacro's values.
TEST(Xacro, LoadYamlRefusesBombsJunkAndBrokenFiles) {
  TempDir dir("servoloop-xacro");
  auto errorOfYaml = [&](const std::string& yaml) {
    writeFile(dir.path() / "config.yaml", yaml);
    writeFile(dir.path() / "r.xacro", std::string(kOpen) +
                                          "\n<l x=\"${len(xacro.load_yaml('config.yaml'))}\"/></robot>");
    try {
      return expandXacroFile(dir.path() / "r.xacro");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
  };
  const std::string yaml_file = (dir.path() / "config.yaml").string();
  // Nine lines whose aliases stand for 10^9 values.
  std::string bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";
  for (char level = 'b'; level <= 'i'; ++level) {
    bomb += std::string(1, level) + ": &" + level + " [";
    for (int k = 0; k < 10; ++k) bomb += std::string(k ? ", *" : "*") + static_cast<char>(level - 1);
    bomb += "]\n";
  }
  const std::string bombed = errorOfYaml(bomb);
  EXPECT_CONTAINS(bombed, "r.xacro:2: xacro: ${len(xacro.load_yaml('config.yaml'))}: load_yaml('config.yaml'): " +
                              yaml_file + ": the YAML holds more than 1000000 values once its aliases");
  EXPECT_LT(bombed.size(), 1000u);
  // Aliases that stay small are read.
  EXPECT_CONTAINS(errorOfYaml("a: &a [1, 2]\nb: *a\n"), "<l x=\"2\"/>");
  const std::string binary = errorOfYaml(std::string("\x7f" "ELF\x02\x01\x01\0\0\0\xff\xfe", 12));
  EXPECT_CONTAINS(binary, "r.xacro:2: xacro: ");
  EXPECT_CONTAINS(binary, yaml_file + ": byte 0 (0x7F) is not text, and a YAML file is UTF-8 text");
  EXPECT_CONTAINS(errorOfYaml(std::string("name: arm\0", 10)), yaml_file + ": byte 9 (0x00) is not text");
  EXPECT_CONTAINS(errorOfYaml("name: caf\xe9\n"), yaml_file + ": byte 9 (0xE9) is not text");
  const std::string broken = errorOfYaml("joints: [1, 2\n");
  EXPECT_CONTAINS(broken, "load_yaml('config.yaml'): " + yaml_file + ":");
  EXPECT_CONTAINS(broken, "not valid YAML");
  EXPECT_EQ(broken.find("yaml-cpp"), std::string::npos) << broken;
  EXPECT_CONTAINS(errorOfYaml(repeated("[", 150) + repeated("]", 150)),
                  yaml_file + ": line 1: maps and lists nest more than 100 levels deep");
  EXPECT_CONTAINS(errorOfYaml(repeated("[", 99) + repeated("]", 99)), "<l x=\"1\"/>");
}

TEST(Xacro, ArgumentsOnTheCommandLineNeedNameColonEquals) {
  EXPECT_EQ(parseXacroArg("prefix:=left_"), (std::pair<std::string, std::string>{"prefix", "left_"}));
  EXPECT_EQ(parseXacroArg("empty:="), (std::pair<std::string, std::string>{"empty", ""}));
  try {
    parseXacroArg("prefix=left_");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_CONTAINS(e.what(), "'prefix=left_' is not name:=value");
  }
}

// A whole robot in xacro loads to the same model as its hand-expanded URDF.
TEST(Xacro, RobotAssetMatchesItsHandExpandedUrdf) {
  const std::string assets = std::string(SERVOLOOP_SOURCE_DIR) + "/tests/assets/xacro/";
  const std::string expanded = expandXacroFile(assets + "two_wheel_arm.urdf.xacro", {{"arm_length", "0.6"}});
  EXPECT_EQ(canonicalXml(expanded), canonicalXml(testing::readFile(assets + "two_wheel_arm_expanded.urdf")));
  const auto model = loadRobotModelFile(assets + "two_wheel_arm.urdf.xacro", {{"arm_length", "0.6"}});
  ASSERT_NE(model->getJoint("arm_joint"), nullptr);
  EXPECT_DOUBLE_EQ(model->getLink("arm")->inertial->mass, 1.2);
  EXPECT_DOUBLE_EQ(model->getJoint("arm_joint")->limits->upper, M_PI / 2);
}

}  // namespace
}  // namespace servoloop
