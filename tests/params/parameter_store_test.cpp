// ParameterStore: the seed's ros_control YAML loads unchanged, typed reads
// follow rosparam's typing, errors name the key/file/line, set/dump round-trip.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "thrown_message.hpp"
#include "servoloop/params/parameter_store.hpp"

#include "servoloop/core/text_file.hpp"
#include "temp_dir.hpp"

namespace servoloop::params {
namespace {

using servoloop::testing::thrownMessage;

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const std::string kSeedParams = std::string(SERVOLOOP_SEED_DIR) + "/control_config/one_dof_ctl_params.yaml";
constexpr const char* kPid = "/one_DOF_robot/joint1_position_controller/pid";

// A file in this test program's own temporary folder.
std::string writeTempFile(const std::string& name, const std::string& content) {
  static const servoloop::testing::TempDir dir("servoloop-parameter-store");
  servoloop::testing::writeFile(dir.path() / name, content);
  return dir.file(name);
}

TEST(ParameterStore, SeedYamlLoadsAsIs) {
  ParameterStore params;
  params.loadFile(kSeedParams);

  EXPECT_EQ(params.get<double>("/one_DOF_robot/joint1_position_controller/pid/i_clamp_min"), -10.0);
  EXPECT_EQ(params.get<double>("/one_DOF_robot/joint1_position_controller/pid/i_clamp_max"), 10.0);
  EXPECT_EQ(params.get<double>("/one_DOF_robot/joint1_position_controller/pid/p"), 10.0);
  EXPECT_EQ(params.get<int>("/one_DOF_robot/joint_state_controller/publish_rate"), 50);
  EXPECT_EQ(params.get<double>("/one_DOF_robot/joint_state_controller/publish_rate"), 50.0);
  EXPECT_EQ(params.get<std::string>("/one_DOF_robot/joint_state_controller/type"),
            "joint_state_controller/JointStateController");
  EXPECT_EQ(params.get<std::string>("/one_DOF_robot/joint1_position_controller/type"),
            "effort_controllers/JointPositionController");
  EXPECT_EQ(params.get<std::string>("/one_DOF_robot/joint1_position_controller/joint"), "joint1");

  // Exactly the nine values of the file, like `rosparam list`.
  EXPECT_THAT(params.list("/one_DOF_robot"),
              ElementsAre("/one_DOF_robot/joint1_position_controller/joint",
                          "/one_DOF_robot/joint1_position_controller/pid/d",
                          "/one_DOF_robot/joint1_position_controller/pid/i",
                          "/one_DOF_robot/joint1_position_controller/pid/i_clamp_max",
                          "/one_DOF_robot/joint1_position_controller/pid/i_clamp_min",
                          "/one_DOF_robot/joint1_position_controller/pid/p",
                          "/one_DOF_robot/joint1_position_controller/type",
                          "/one_DOF_robot/joint_state_controller/publish_rate",
                          "/one_DOF_robot/joint_state_controller/type"));
  EXPECT_THAT(params.childNames("/one_DOF_robot"),
              ElementsAre("joint1_position_controller", "joint_state_controller"));
  EXPECT_TRUE(params.has("/one_DOF_robot/joint1_position_controller/pid"));
  EXPECT_FALSE(params.has("/one_DOF_robot/joint2_position_controller"));
  // Line 5, column 19 of the seed file is the 50 of publish_rate.
  EXPECT_EQ(params.sourceOf("/one_DOF_robot/joint_state_controller/publish_rate"), kSeedParams + ":5:19");
}

TEST(ParameterStore, LoadsUnderANamespaceAndResolvesRelativeNames) {
  ParameterStore params;
  params.loadFile(kSeedParams, "/sim");
  EXPECT_EQ(params.get<double>("/sim/one_DOF_robot/joint1_position_controller/pid/d"), 10.0);
  EXPECT_EQ(params.get<double>("sim/one_DOF_robot/joint1_position_controller/pid/d"), 10.0);
  EXPECT_FALSE(params.has("/one_DOF_robot"));

  EXPECT_EQ(resolveName("/one_DOF_robot", "joint1_position_controller/pid/p"),
            "/one_DOF_robot/joint1_position_controller/pid/p");
  EXPECT_EQ(resolveName("/one_DOF_robot/", "/other/x"), "/other/x");
  EXPECT_EQ(resolveName("/", "a//b/"), "/a/b");
  EXPECT_EQ(resolveName("", ""), "/");
  EXPECT_THAT(thrownMessage<Error>([] { resolveName("/ns", "~private"); }), HasSubstr("'~' names are not supported"));
}

TEST(ParameterStore, TypeErrorsNameKeyExpectedAndActualTypes) {
  ParameterStore params;
  params.loadFile(kSeedParams);

  const std::string rate_as_string = thrownMessage<ParameterTypeError>(
      [&] { params.get<std::string>("/one_DOF_robot/joint_state_controller/publish_rate"); });
  EXPECT_THAT(rate_as_string, HasSubstr("'/one_DOF_robot/joint_state_controller/publish_rate'"));
  EXPECT_THAT(rate_as_string, HasSubstr("is int 50, expected string"));
  EXPECT_THAT(rate_as_string, HasSubstr("one_dof_ctl_params.yaml:5:19"));

  // A double is not an int, as for rosparam.
  const std::string p_as_int = thrownMessage<ParameterTypeError>([&] { params.get<int>(std::string(kPid) + "/p"); });
  EXPECT_THAT(p_as_int, HasSubstr("'/one_DOF_robot/joint1_position_controller/pid/p'"));
  EXPECT_THAT(p_as_int, HasSubstr("is double 10.0, expected int"));

  const std::string type_as_double = thrownMessage<ParameterTypeError>(
      [&] { params.get<double>("/one_DOF_robot/joint1_position_controller/type"); });
  EXPECT_THAT(type_as_double,
              HasSubstr("is string \"effort_controllers/JointPositionController\", expected double"));

  const std::string pid_as_list =
      thrownMessage<ParameterTypeError>([&] { params.get<std::vector<double>>(kPid); });
  EXPECT_THAT(pid_as_list, HasSubstr("is map"));
  EXPECT_THAT(pid_as_list, HasSubstr("expected list of double"));

  EXPECT_THROW(params.get<bool>(std::string(kPid) + "/p"), ParameterTypeError);
}

TEST(ParameterStore, MissingNameSaysWhatTheNamespaceHas) {
  ParameterStore params;
  params.loadFile(kSeedParams);
  const std::string message =
      thrownMessage<ParameterNotFoundError>([&] { params.get<double>(std::string(kPid) + "/pp"); });
  EXPECT_THAT(message, HasSubstr("parameter '/one_DOF_robot/joint1_position_controller/pid/pp' not found"));
  EXPECT_THAT(message, HasSubstr("'/one_DOF_robot/joint1_position_controller/pid' has: d, i, i_clamp_max, "
                                 "i_clamp_min, p"));

  const std::string deep =
      thrownMessage<ParameterNotFoundError>([&] { params.get<double>("/one_DOF_robot/nope/pid/p"); });
  EXPECT_THAT(deep, HasSubstr("'/one_DOF_robot' has: joint1_position_controller, joint_state_controller"));

  EXPECT_EQ(params.get(std::string(kPid) + "/pp", 2.5), 2.5);
  EXPECT_EQ(params.get(std::string(kPid) + "/p", 2.5), 10.0);
  EXPECT_EQ(params.get("/nothing/here", "fallback"), "fallback");
  // A present value of the wrong type is an error even with a default.
  EXPECT_THROW(params.get("/one_DOF_robot/joint1_position_controller/joint", 1.0), ParameterTypeError);

  double out = -1.0;
  EXPECT_FALSE(params.tryGet("/missing", out));
  EXPECT_EQ(out, -1.0);
  EXPECT_TRUE(params.tryGet(std::string(kPid) + "/i", out));
  EXPECT_EQ(out, 10.0);
}

TEST(ParameterStore, MalformedYamlNamesFileAndLine) {
  // Line 3 opens a flow list that line 4 never closes.
  const std::string path = writeTempFile("servoloop_h4_broken_params.yaml",
                                         "robot:\n"
                                         "  ctrl:\n"
                                         "    gains: [1.0, 2.0\n"
                                         "    joint: j1\n");
  ParameterStore params;
  const std::string message = thrownMessage<ConfigError>([&] { params.loadFile(path); });
  EXPECT_THAT(message, HasSubstr(path + ":4:"));
  EXPECT_THAT(message, HasSubstr("invalid YAML"));
  EXPECT_THAT(message, HasSubstr("closed brackets"));
  std::filesystem::remove(path);

  const std::string missing = thrownMessage<ConfigError>([&] { params.loadFile("/no/such/dir/params.yaml"); });
  EXPECT_THAT(missing, HasSubstr("/no/such/dir/params.yaml: parameter file not found"));
  EXPECT_THAT(missing, HasSubstr("check the path"));

  // A device is refused before a byte is read (/dev/zero would never end).
  const std::string device = thrownMessage<ConfigError>([&] { params.loadFile("/dev/zero"); });
  EXPECT_THAT(device, HasSubstr("/dev/zero: is not a regular file (a device, FIFO or socket)"));
  const std::string folder = thrownMessage<ConfigError>([&] { params.loadFile("/tmp"); });
  EXPECT_THAT(folder, HasSubstr("/tmp: is a folder, not a parameter file"));
  // Nine lines whose aliases stand for 10^9 values.
  std::string bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";
  for (char level = 'b'; level <= 'i'; ++level) {
    bomb += std::string(1, level) + ": &" + level + " [";
    for (int k = 0; k < 10; ++k) bomb += std::string(k ? ", *" : "*") + static_cast<char>(level - 1);
    bomb += "]\n";
  }
  const std::string bomb_file = writeTempFile("bomb.yaml", bomb);
  const std::string bombed = thrownMessage<ConfigError>([&] { params.loadFile(bomb_file); });
  EXPECT_THAT(bombed, HasSubstr(bomb_file + ": the YAML holds more than 1000000 values once its aliases"));
  EXPECT_FALSE(params.has("/a")) << "nothing of the refused file is loaded";

  // A key twice in one map: ROS would take the last, yaml-cpp the first.
  const std::string twice =
      thrownMessage<ConfigError>([&] { params.loadString("ctrl:\n  pid: {p: 10, d: 1, p: 20}\n", "dup.yaml"); });
  EXPECT_THAT(twice, HasSubstr("dup.yaml:2:"));
  EXPECT_THAT(twice, HasSubstr("key 'p' appears twice in one map (first at line 2)"));
  EXPECT_FALSE(params.has("/ctrl"));

  // A file over the limit is refused by its size (a sparse file: nothing is written).
  const servoloop::testing::TempDir big_dir("servoloop-parameter-store-big");
  const std::string big = big_dir.file("huge.yaml");
  servoloop::testing::writeFile(big, "a: 1\n");
  std::filesystem::resize_file(big, kMaxTextFileBytes + (std::uintmax_t{1} << 20));
  const std::string huge = thrownMessage<ConfigError>([&] { params.loadFile(big); });
  EXPECT_THAT(huge, HasSubstr(big + ": parameter file of 65 MiB; the limit is 64 MiB"));

  const std::string top_list = thrownMessage<ConfigError>([&] { params.loadString("- 1\n- 2\n", "list.yaml"); });
  EXPECT_THAT(top_list, HasSubstr("list.yaml: the top level is a list, expected a map"));

  EXPECT_NO_THROW(params.loadString("", "empty.yaml"));
  EXPECT_TRUE(params.list().empty());
}

// checkYamlSize is checkYamlDocument's node count alone (xacro's load_yaml
// takes a key given twice as Python does).
TEST(ParameterStore, CheckYamlSizeCountsNodesAndLetsAKeyRepeat) {
  const YAML::Node twice = YAML::Load("pid: {p: 10, p: 20}");
  EXPECT_NO_THROW(checkYamlSize(twice, "twice.yaml"));
  EXPECT_THAT(thrownMessage<ConfigError>([&] { checkYamlDocument(twice, "twice.yaml"); }),
              HasSubstr("key 'p' appears twice"));
  std::string bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";
  for (char level = 'b'; level <= 'g'; ++level) {
    bomb += std::string(1, level) + ": &" + level + " [";
    for (int k = 0; k < 10; ++k) bomb += std::string(k ? ", *" : "*") + static_cast<char>(level - 1);
    bomb += "]\n";
  }
  EXPECT_THAT(thrownMessage<ConfigError>([&] { checkYamlSize(YAML::Load(bomb), "bomb.yaml"); }),
              HasSubstr("bomb.yaml: the YAML holds more than 1000000 values once its aliases"));
}

TEST(ParameterStore, ScalarsAreTypedLikeYaml) {
  ParameterStore params;
  params.loadString(
      "a: 1\n"
      "b: 1.5\n"
      "c: \"1\"\n"
      "d: yes\n"
      "e: -2.5e-3\n"
      "f: .inf\n"
      "g: [1, 2.5, -3]\n"
      "h: [joint1, joint2]\n"
      "i: 0x10\n"
      "nested/key: {x: 2}\n",
      "inline.yaml");
  EXPECT_EQ(params.get<int>("a"), 1);
  EXPECT_EQ(params.get<double>("a"), 1.0);
  EXPECT_EQ(params.get<double>("b"), 1.5);
  EXPECT_EQ(params.get<std::string>("c"), "1");
  EXPECT_THROW(params.get<int>("c"), ParameterTypeError);
  EXPECT_TRUE(params.get<bool>("d"));
  EXPECT_EQ(params.get<double>("e"), -0.0025);
  EXPECT_EQ(params.get<double>("f"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(params.get<std::vector<double>>("g"), (std::vector<double>{1.0, 2.5, -3.0}));
  EXPECT_THAT(thrownMessage<ParameterTypeError>([&] { params.get<std::vector<int>>("g"); }),
              HasSubstr("'/g[1]'"));
  EXPECT_EQ(params.get<std::vector<std::string>>("h"), (std::vector<std::string>{"joint1", "joint2"}));
  EXPECT_EQ(params.get<int>("i"), 16);
  // Keys with '/' nest, as with rosparam.
  EXPECT_EQ(params.get<int>("/nested/key/x"), 2);
}

TEST(ParameterStore, LaterFilesMergeMapsAndReplaceValues) {
  ParameterStore params;
  params.loadString("ctrl: {pid: {p: 1.0, i: 2.0}, joint: j1}\n", "first.yaml");
  params.loadString("ctrl: {pid: {i: 5.0, d: 0.5}}\n", "second.yaml");
  EXPECT_EQ(params.get<double>("/ctrl/pid/p"), 1.0);
  EXPECT_EQ(params.get<double>("/ctrl/pid/i"), 5.0);
  EXPECT_EQ(params.get<double>("/ctrl/pid/d"), 0.5);
  EXPECT_EQ(params.get<std::string>("/ctrl/joint"), "j1");
  EXPECT_THAT(params.sourceOf("/ctrl/pid/i"), HasSubstr("second.yaml:1:"));
  EXPECT_THAT(params.sourceOf("/ctrl/pid/p"), HasSubstr("first.yaml:1:"));
}

TEST(ParameterStore, SetTypesStringValuesLikeRosparam) {
  ParameterStore params;
  params.set("/robot/x", "1.0");
  params.set("/robot/n", "3");
  params.set("/robot/flag", "true");
  params.set("/robot/gains", "[1, 2]");
  params.set("/robot/name", "hello world");
  params.set("/robot/pid", "{p: 4.0, d: 1}");
  params.setString("/robot/quoted", "10");

  EXPECT_EQ(params.get<double>("/robot/x"), 1.0);
  EXPECT_THROW(params.get<int>("/robot/x"), ParameterTypeError);
  EXPECT_EQ(params.get<int>("/robot/n"), 3);
  EXPECT_EQ(params.get<double>("/robot/n"), 3.0);
  EXPECT_TRUE(params.get<bool>("/robot/flag"));
  EXPECT_EQ(params.get<std::vector<double>>("/robot/gains"), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(params.get<std::string>("/robot/name"), "hello world");
  EXPECT_EQ(params.get<double>("/robot/pid/p"), 4.0);
  EXPECT_EQ(params.get<int>("/robot/pid/d"), 1);
  EXPECT_EQ(params.get<std::string>("/robot/quoted"), "10");
  EXPECT_EQ(params.sourceOf("/robot/x"), "set");

  // Typed setters keep their type.
  params.set("/robot/t", 2.0);
  params.set("/robot/k", 7);
  params.set("/robot/b", false);
  params.set("/robot/joints", std::vector<std::string>{"true", "j2"});
  EXPECT_THROW(params.get<int>("/robot/t"), ParameterTypeError);
  EXPECT_EQ(params.get<double>("/robot/t"), 2.0);
  EXPECT_EQ(params.get<int>("/robot/k"), 7);
  EXPECT_FALSE(params.get<bool>("/robot/b"));
  EXPECT_EQ(params.get<std::vector<std::string>>("/robot/joints"), (std::vector<std::string>{"true", "j2"}));

  // Setting below a value turns it into a namespace; set replaces a whole map.
  params.set("/robot/x/sub", 1);
  EXPECT_EQ(params.get<int>("/robot/x/sub"), 1);
  params.set("/robot/pid", "{i: 9.0}");
  EXPECT_FALSE(params.has("/robot/pid/p"));
  EXPECT_EQ(params.get<double>("/robot/pid/i"), 9.0);

  EXPECT_TRUE(params.remove("/robot/pid"));
  EXPECT_FALSE(params.remove("/robot/pid"));
  EXPECT_FALSE(params.has("/robot/pid/i"));
}

// `param set -N /robot "" 1` must not replace the whole namespace, and no
// name a reader cannot read back (a private '~' name, other characters) is stored.
TEST(ParameterStore, SettersRefuseNamesThatAreNotRosNames) {
  ParameterStore params;
  params.loadString("robot: {controller: {pid: {p: 1.0}}}", "robot.yaml");
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("", "1"); }), HasSubstr("parameter name '' is empty"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.setNode("", YAML::Load("{a: 1}")); }), HasSubstr("is empty"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("~private", "1"); }),
              HasSubstr("'~private' is a private '~' name"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("~private", 1); }), HasSubstr("give the full name"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.setString("/robot/~x", "v"); }),
              HasSubstr("'/robot/~x' is not a ROS graph resource name"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("/robot/a b", 1.0); }), HasSubstr("'/robot/a b'"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("1abc", true); }), HasSubstr("must start with a letter or '/'"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set(std::string(2000, 'a'), 1); }), HasSubstr("at most 1024"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.set("/robot", "{~p: 1}"); }), HasSubstr("private '~' name"));
  EXPECT_THAT(thrownMessage<Error>([&] { params.loadString("a: 1", "a.yaml", "~ns"); }), HasSubstr("'~ns'"));
  // Nothing was stored, and the namespace is whole.
  EXPECT_EQ(params.list("/"), (std::vector<std::string>{"/robot/controller/pid/p"}));
  EXPECT_EQ(params.get<double>("/robot/controller/pid/p"), 1.0);
  // Names that are ROS names still work.
  params.set("robot/controller/pid/i", "0.5");
  params.set("/robot/controller/pid/d_2/", 0.1);
  EXPECT_EQ(params.get<double>("/robot/controller/pid/i"), 0.5);
  EXPECT_EQ(params.get<double>("/robot/controller/pid/d_2"), 0.1);
}

TEST(ParameterStore, DumpReadsBackToTheSameValuesAndTypes) {
  ParameterStore original;
  original.loadFile(kSeedParams);
  original.setString("/one_DOF_robot/label", "10");
  original.setString("/one_DOF_robot/switch", "on");
  original.set("/one_DOF_robot/gains", std::vector<double>{0.5, 1.0, 2.0});
  original.set("/one_DOF_robot/empty", "{}");

  const std::string text = original.dump("/");
  ParameterStore copy;
  copy.loadString(text, "dump.yaml");

  EXPECT_EQ(copy.list(), original.list());
  EXPECT_EQ(copy.dump("/"), text);
  EXPECT_EQ(copy.get<std::string>("/one_DOF_robot/label"), "10");
  EXPECT_EQ(copy.get<std::string>("/one_DOF_robot/switch"), "on");
  EXPECT_EQ(copy.get<std::vector<double>>("/one_DOF_robot/gains"), (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(copy.get<double>(std::string(kPid) + "/i_clamp_min"), -10.0);
  EXPECT_THROW(copy.get<int>(std::string(kPid) + "/i_clamp_min"), ParameterTypeError);
  EXPECT_EQ(copy.get<int>("/one_DOF_robot/joint_state_controller/publish_rate"), 50);

  // A sub-namespace dumps relative to itself.
  ParameterStore pid;
  pid.loadString(original.dump(kPid), "pid.yaml", "/gains");
  EXPECT_EQ(pid.get<double>("/gains/i_clamp_max"), 10.0);
}

TEST(ParameterStore, NodeIsADeepCopyOfTheSubtree) {
  ParameterStore params;
  params.loadFile(kSeedParams);
  YAML::Node controller = params.node("/one_DOF_robot/joint1_position_controller");
  EXPECT_EQ(controller["joint"].as<std::string>(), "joint1");
  EXPECT_EQ(controller["pid"]["p"].as<double>(), 10.0);
  controller["pid"]["p"] = 99.0;
  EXPECT_EQ(params.get<double>(std::string(kPid) + "/p"), 10.0);
  EXPECT_THROW(params.node("/one_DOF_robot/joint9_controller"), ParameterNotFoundError);
}

TEST(ParameterStore, ConcurrentReadersAndWritersSeeWholeValues) {
  ParameterStore params;
  params.set("/counter", std::vector<double>{0.0, 0.0, 0.0});
  std::thread writer([&] {
    for (int k = 1; k <= 2000; ++k) {
      const double v = k;
      params.set("/counter", std::vector<double>{v, v, v});
    }
  });
  int reads = 0;
  for (; reads < 2000; ++reads) {
    const auto values = params.get<std::vector<double>>("/counter");
    ASSERT_EQ(values.size(), 3u);
    ASSERT_EQ(values[0], values[1]);
    ASSERT_EQ(values[1], values[2]);
  }
  writer.join();
  EXPECT_EQ(params.get<std::vector<double>>("/counter"), (std::vector<double>{2000.0, 2000.0, 2000.0}));
}

}  // namespace
}  // namespace servoloop::params
