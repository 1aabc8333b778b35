// The bad-input suite: a table of malformed inputs (cases/*.yaml), each run
// through the `servoloop` executable as a user would, each with the words its
// one error must contain. Most cases start from one of the repository's own
// working files and change one thing in it, so the change is what is wrong;
// the unchanged files are run first and must pass.
//
// Every case must end in one clear error: a non-zero exit status (not a
// signal, not a hang), the expected words on stderr, no raw library or
// crash text, and four lines at most besides progress (`max_lines` where a
// case breaks several things at once). `warning` cases run and exit 0
// with the words on stderr. Cases of the families `ipc` and `client` go to one
// live node (the seed robot on the mock backend at real-time factor 1): a raw
// request line on its socket, or a client command; after each the node must
// still answer. The per-family counts are printed at the end.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "child_process.hpp"
#include "ipc_test_support.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "temp_dir.hpp"
#include "wait_until.hpp"

namespace {

namespace fs = std::filesystem;
using servoloop::testing::ProcessOptions;
using servoloop::testing::TempDir;

const fs::path kSource = SERVOLOOP_SOURCE_DIR;
const fs::path kCases = kSource / "tests" / "bad_input" / "cases";

struct Edit {
  std::string file;
  std::string from;
  std::string to;
};

struct Case {
  std::string source;  // cases file and index, for messages
  std::string family;
  std::string what;
  std::vector<std::string> copy;  // repository paths copied into the case's folder
  std::map<std::string, std::string> write;
  std::vector<Edit> edits;
  std::map<std::string, std::string> environment;
  std::string setup;  // shell commands run in the case's folder first
  std::string run;   // arguments after `servoloop` (shell words), or
  std::string send;  // a raw request line for the live node (family ipc)
  bool warning = false;
  int max_lines = 4;  // lines of stderr that are not progress ("[I] ...")
  std::vector<std::string> expect;
};

std::vector<std::string> strings(const YAML::Node& node) {
  std::vector<std::string> out;
  if (!node) return out;
  if (node.IsScalar()) return {node.as<std::string>()};
  for (const auto& item : node) out.push_back(item.as<std::string>());
  return out;
}

std::vector<Case> loadCases() {
  std::vector<Case> cases;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kCases))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    YAML::Node root;
    try {
      root = YAML::LoadFile(file.string());
    } catch (const YAML::Exception& error) {
      throw std::runtime_error(file.string() + ": " + error.what());
    }
    const std::string family = root["family"].as<std::string>();
    const YAML::Node defaults = root["defaults"];
    int index = 0;
    for (const auto& node : root["cases"]) {
      Case c;
      c.source = file.filename().string() + " case " + std::to_string(index++);
      c.family = family;
      c.what = node["what"].as<std::string>();
      auto field = [&](const char* key) { return node[key] ? node[key] : defaults ? defaults[key] : YAML::Node(); };
      c.copy = strings(field("copy"));
      if (const YAML::Node write = field("write"))
        for (const auto& item : write) c.write[item.first.as<std::string>()] = item.second.as<std::string>();
      if (const YAML::Node environment = field("env"))
        for (const auto& item : environment)
          c.environment[item.first.as<std::string>()] = item.second.as<std::string>();
      if (const YAML::Node edits = node["edit"]) {
        const std::string default_file = field("file") ? field("file").as<std::string>() : "";
        auto add = [&](const YAML::Node& e) {
          c.edits.push_back({e["file"] ? e["file"].as<std::string>() : default_file, e["from"].as<std::string>(),
                             e["to"].as<std::string>()});
        };
        if (edits.IsSequence())
          for (const auto& e : edits) add(e);
        else
          add(edits);
      }
      if (const YAML::Node run = field("run")) c.run = run.as<std::string>();
      if (node["setup"]) c.setup = node["setup"].as<std::string>();
      if (node["send"]) c.send = node["send"].as<std::string>();
      if (const YAML::Node repeat = node["repeat"]) {
        std::string text;
        const std::string unit = repeat["text"].as<std::string>();
        for (int i = repeat["times"].as<int>(); i > 0; --i) text += unit;
        const auto at = c.send.find("@@");
        if (at != std::string::npos) c.send.replace(at, 2, text);
      }
      c.warning = node["warning"] && node["warning"].as<bool>();
      if (node["max_lines"]) c.max_lines = node["max_lines"].as<int>();
      c.expect = strings(node["expect"]);
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

// Text that means a crash, an escaped exception or a library's raw message
// rather than servoloop's own error.
const std::vector<std::string> kRawText = {
    "terminate called", "what():",  "Segmentation", "Aborted",       "AddressSanitizer", "runtime error:",
    "[json.exception",  "std::",    "basic_string", "yaml-cpp: error", "Assertion",      "core dumped"};

// Lines of stderr that are not progress ("[I] ..."): the error and its warnings.
int problemLines(const std::string& err) {
  int count = 0;
  std::size_t start = 0;
  while (start < err.size()) {
    std::size_t end = err.find('\n', start);
    if (end == std::string::npos) end = err.size();
    if (end > start && err.compare(start, 4, "[I] ") != 0) ++count;
    start = end + 1;
  }
  return count;
}

std::string describe(const Case& c) { return c.source + " (" + c.family + ": " + c.what + ")"; }

class BadInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { cases_ = new std::vector<Case>(loadCases()); }
  static void TearDownTestSuite() {
    delete cases_;
    cases_ = nullptr;
  }

  // Builds the case's folder: copies, writes, then edits (each edit's text
  // must be there: a case whose base file moved on fails instead of passing).
  static void prepare(const Case& c, const fs::path& dir) {
    for (const auto& path : c.copy) {
      const fs::path from = kSource / path;
      ASSERT_TRUE(fs::exists(from)) << describe(c) << ": no " << from;
      fs::copy(from, dir / from.filename(), fs::copy_options::recursive);
    }
    for (const auto& [name, content] : c.write) servoloop::testing::writeFile(dir / name, content);
    for (const auto& edit : c.edits) {
      const fs::path file = dir / edit.file;
      std::string text = servoloop::testing::readFile(file);
      const auto at = text.find(edit.from);
      ASSERT_NE(at, std::string::npos) << describe(c) << ": '" << edit.from << "' is not in " << edit.file;
      text.replace(at, edit.from.size(), edit.to);
      servoloop::testing::writeFile(file, text);
    }
    if (!c.setup.empty()) {
      const auto result = servoloop::testing::runShell(c.setup, ProcessOptions{dir, dir, {}}, 30.0);
      ASSERT_EQ(result.status, 0) << describe(c) << ": setup '" << c.setup << "' failed: " << result.err;
    }
  }

  static servoloop::testing::ProcessResult runCli(const std::string& args, const fs::path& dir,
                                                  const fs::path& run_dir,
                                                  const std::map<std::string, std::string>& environment) {
    ProcessOptions options{dir, dir, {{"SERVOLOOP_PLUGIN_PATH", std::nullopt},
                                      {"ROS_PACKAGE_PATH", std::nullopt},
                                      {"SERVOLOOP_RUN_DIR", run_dir.string()}}};
    options.environment["SERVOLOOP_EXE"] = SERVOLOOP_CLI_EXE;
    for (const auto& [name, value] : environment) options.environment[name] = value;
    // A case of two commands (`... && exec "$SERVOLOOP_EXE" ...`) runs in the
    // shell; a single command replaces it, so a signal shows as one.
    const bool two_commands = args.find("&&") != std::string::npos;
    return servoloop::testing::runShell(std::string(two_commands ? "'" : "exec '") + SERVOLOOP_CLI_EXE + "' " + args,
                                        options, 60.0);
  }

  // The checks every error (or warning) must pass; failures name the case.
  static void checkOutcome(const Case& c, const servoloop::testing::ProcessResult& result) {
    const std::string who = describe(c) + "\n  servoloop " + c.run + "\n  stderr: " + result.err;
    ASSERT_FALSE(result.timed_out) << who;
    ASSERT_NE(result.status, -1) << "killed by a signal: " << who;
    ASSERT_LT(result.status, 128) << "killed by a signal: " << who;
    if (c.warning) {
      EXPECT_EQ(result.status, 0) << who;
    } else {
      EXPECT_NE(result.status, 0) << who;
      EXPECT_LE(problemLines(result.err), c.max_lines) << "one error, not a dump: " << who;
    }
    for (const auto& word : c.expect) EXPECT_NE(result.err.find(word), std::string::npos) << "'" << word << "' " << who;
    for (const auto& raw : kRawText) EXPECT_EQ(result.err.find(raw), std::string::npos) << "'" << raw << "' " << who;
  }

  static std::vector<Case>* cases_;
};

std::vector<Case>* BadInput::cases_ = nullptr;

// One raw line to a node's socket and its one reply line ("" when none).
std::string exchange(const fs::path& socket_path, const std::string& line) {
  return servoloop::ipc::testing::requestLine(socket_path, line, 20.0).value_or("");
}

TEST_F(BadInput, TheUnchangedBaseFilesPass) {
  TempDir temp{"servoloop-bad-input-base"};
  const fs::path run_dir = temp.path() / "run";
  fs::create_directories(run_dir);
  fs::permissions(run_dir, fs::perms::owner_all, fs::perm_options::replace);
  std::map<std::string, int> checked;
  for (const Case& c : *cases_) {
    if (c.family == "ipc" || c.family == "client" || c.edits.empty()) continue;
    const std::string key = c.run + "|" + ::testing::PrintToString(c.copy) + ::testing::PrintToString(c.write);
    if (checked.count(key)) continue;
    Case base = c;
    base.edits.clear();
    const fs::path dir = temp.path() / ("base" + std::to_string(checked.size()));
    fs::create_directories(dir);
    prepare(base, dir);
    const auto result = runCli(c.run, dir, run_dir, c.environment);
    EXPECT_EQ(result.status, 0) << "the base of " << describe(c) << " fails unchanged:\n  servoloop " << c.run
                                << "\n  " << result.err;
    checked[key] = result.status;
  }
  EXPECT_GE(checked.size(), 5u);
}

TEST_F(BadInput, EveryCaseGetsOneClearErrorAndTheNodeServesOn) {
  TempDir temp{"servoloop-bad-input"};
  const fs::path run_dir = temp.path() / "run";
  fs::create_directories(run_dir);
  fs::permissions(run_dir, fs::perms::owner_all, fs::perm_options::replace);
  ::setenv("SERVOLOOP_RUN_DIR", run_dir.c_str(), 1);
  // Commands that are not meant for the node see a run folder with no node.
  const fs::path empty_run_dir = temp.path() / "run-empty";
  fs::create_directories(empty_run_dir);
  fs::permissions(empty_run_dir, fs::perms::owner_all, fs::perm_options::replace);

  // The live node for the ipc and client families.
  const fs::path node_dir = temp.path() / "node";
  fs::create_directories(node_dir);
  servoloop::testing::ChildProcess node(
      {SERVOLOOP_CLI_EXE, "launch", (kSource / "robots/one_dof/one_dof_w_jnt_ctl.launch.yaml").string(), "--backend",
       "mock"},
      {node_dir, node_dir, {{"SERVOLOOP_PLUGIN_PATH", std::nullopt}, {"SERVOLOOP_RUN_DIR", run_dir.string()}}});
  const fs::path robot_socket = servoloop::ipc::socketPathFor("/one_DOF_robot");
  auto pingOk = [&] {
    const std::string reply = exchange(robot_socket, R"({"id": 1, "op": "ping"})");
    return reply.find("\"ok\":true") != std::string::npos;
  };
  ASSERT_TRUE(servoloop::testing::waitUntil(pingOk, std::chrono::seconds(60))) << node.currentErr();

  std::map<std::string, int> per_family;
  int index = 0;
  for (const Case& c : *cases_) {
    const fs::path dir = temp.path() / ("case" + std::to_string(index++));
    fs::create_directories(dir);
    prepare(c, dir);
    if (c.family == "ipc") {
      const std::string reply = exchange(robot_socket, c.send);
      const std::string who = describe(c) + "\n  sent: " + c.send.substr(0, 200) + "\n  reply: " + reply.substr(0, 400);
      nlohmann::json parsed = nlohmann::json::parse(reply, nullptr, false);
      ASSERT_TRUE(parsed.is_object()) << who;
      EXPECT_EQ(parsed.value("ok", true), false) << who;
      const std::string error = parsed.value("error", "");
      for (const auto& word : c.expect) EXPECT_NE(error.find(word), std::string::npos) << "'" << word << "' " << who;
    } else {
      checkOutcome(c, runCli(c.run, dir, c.family == "client" ? run_dir : empty_run_dir, c.environment));
    }
    if (c.family == "ipc" || c.family == "client") {
      ASSERT_TRUE(pingOk()) << "the node stopped answering after " << describe(c) << "\n" << node.currentErr();
    }
    ++per_family[c.family];
  }

  node.signal(SIGINT);
  const auto node_result = node.wait(60.0);
  EXPECT_EQ(node_result.status, 0) << "the node did not end cleanly after the suite: " << node_result.err;

  std::string table = "bad-input suite:";
  for (const auto& [family, count] : per_family) table += " " + family + " " + std::to_string(count) + ",";
  table += " total " + std::to_string(index);
  std::printf("%s\n", table.c_str());
  RecordProperty("families", table);
  EXPECT_GE(index, 150);
}

}  // namespace
