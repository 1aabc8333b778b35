#include "servoloop/node/roslaunch_xml.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"
#include "servoloop/core/text_file.hpp"
#include "servoloop/core/xml_error_text.hpp"
#include "servoloop/description/package_path.hpp"
#include "servoloop/description/xacro.hpp"
#include "servoloop/node/robot_namespace.hpp"
#include "servoloop/node/sdf_world_launch.hpp"
#include "servoloop/params/parameter_store.hpp"

namespace servoloop::node {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

// Includes nest at most this deep (a file that includes itself stops here).
constexpr int kMaxIncludeDepth = 50;

// Where an element is: "file:line".
struct Place {
  std::string file;
  int line = 0;
  std::string text() const { return file + ":" + std::to_string(line); }
};

// A robot description parameter (<param textfile=...> or command="xacro ...").
struct Description {
  fs::path file;
  XacroArgs xacro_args;
  std::string unusable;  // why it cannot be a robot description ("" when it can)
};

struct SpawnModel {
  Place place;
  std::string description_param;  // resolved name, or "" with -file
  fs::path file;
  std::string model;
  std::string robot_namespace;    // -robot_namespace, else the node's namespace
  std::array<double, 6> pose{};
  bool pose_given = false;
  std::map<std::string, std::string> initial_positions;  // -J, as written (checked to be a number)
};

struct Spawner {
  Place place;
  std::string ns;
  std::vector<std::string> controllers;
  bool stopped = false;
};

// One launch file being read: its arguments and the namespace of the
// elements being read (<group ns> and <include ns> change it).
struct FileScope {
  fs::path file;
  std::map<std::string, std::string> passed;  // from the includer or the command line
  std::set<std::string> used;                 // passed arguments that were declared
  std::map<std::string, std::string> args;    // declared and set
  std::map<std::string, int> arg_lines;       // where each <arg> was declared
  std::string ns = "/";
};

bool truthValue(const std::string& text, bool& value) {
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == "true" || lower == "1") {
    value = true;
    return true;
  }
  if (lower == "false" || lower == "0") {
    value = false;
    return true;
  }
  return false;
}

// Splits an args="..." string into words as a shell does (quotes group).
std::vector<std::string> splitWords(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (char c : text) {
    if (quote != 0) {
      if (c == quote) {
        quote = 0;
      } else {
        word += c;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

class Reader {
 public:
  explicit Reader(const std::map<std::string, std::string>& args) : command_line_args_(args) {}

  LaunchFile read(const fs::path& path) {
    FileScope scope;
    scope.file = fs::absolute(path).lexically_normal();
    scope.passed = command_line_args_;
    readFile(scope, 0);
    return assemble(scope.file);
  }

 private:
  // ----- files and elements -----

  void readFile(FileScope& scope, int depth) {
    // (What exists but is no regular file, readTextFile names as such.)
    std::error_code ec;
    if (!fs::exists(scope.file, ec)) {
      throw ConfigError("launch file '" + scope.file.string() + "' cannot be read (no such file); check the path");
    }
    const std::string text = readTextFile(scope.file, "launch file");
    auto document = std::make_unique<tinyxml2::XMLDocument>();
    if (document->Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
      throw ConfigError(fmt::format("{}:{}: not well-formed roslaunch XML: {}", scope.file.string(),
                                    document->ErrorLineNum(), xmlErrorWords(document->ErrorName(), document->ErrorStr())));
    }
    refuseDocumentTypes(*document, scope);
    const XMLElement* root = document->RootElement();
    if (root == nullptr || std::string(root->Name()) != "launch") {
      throw ConfigError(scope.file.string() + ": a roslaunch file has <launch> as its root element" +
                        (root ? std::string(", not <") + root->Name() + ">" : std::string()));
    }
    if (depth > kMaxIncludeDepth) {
      throw ConfigError(scope.file.string() + ": includes nest more than " + std::to_string(kMaxIncludeDepth) +
                        " deep; does a launch file include itself?");
    }
    documents_.push_back(std::move(document));
    walk(root, scope, depth);
    std::vector<std::string> unused;
    for (const auto& [name, value] : scope.passed) {
      if (scope.used.count(name) == 0) unused.push_back(name);
    }
    if (!unused.empty()) {
      std::string declared;
      for (const auto& [name, value] : scope.args) declared += (declared.empty() ? "" : ", ") + name;
      throw ConfigError(fmt::format("{}: argument(s) {} are not declared by this launch file (its <arg>s: {}); "
                                    "remove them or fix their names",
                                    scope.file.string(), fmt::join(unused, ", "), declared.empty() ? "none" : declared));
    }
  }

  // A <!DOCTYPE> (and the <!ENTITY>s it declares) anywhere in the file.
  // roslaunch files have no DTD, and entity declarations are the stuff of XML
  // bombs; tinyxml2 would not expand them either (an &name; would stay as
  // written), so the file is refused rather than read differently.
  static void refuseDocumentTypes(const tinyxml2::XMLDocument& document, const FileScope& scope) {
    std::vector<const tinyxml2::XMLNode*> pending{&document};
    while (!pending.empty()) {
      const tinyxml2::XMLNode* node = pending.back();
      pending.pop_back();
      if (const tinyxml2::XMLUnknown* unknown = node->ToUnknown()) {
        const std::string text = unknown->Value() ? unknown->Value() : "";
        std::string keyword;
        for (char c : text) {
          if (!std::isalpha(static_cast<unsigned char>(c))) break;
          keyword += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        }
        const bool entity = text.find("ENTITY") != std::string::npos;
        throw ConfigError(fmt::format(
            "{}:{}: <!{}...> is refused: a roslaunch file has no document type{}, and entity declarations are a "
            "classic XML bomb (servoloop's XML reader would not expand them either, so &name; would stay as "
            "written); remove the <!{}...> and write the values out, or declare them with <arg name=\"...\" "
            "default=\"...\"/> and use $(arg name)",
            scope.file.string(), node->GetLineNum(), keyword.empty() ? "?" : keyword,
            entity ? " (DTD) and no <!ENTITY>" : " (DTD)", keyword.empty() ? "?" : keyword));
      }
      for (const tinyxml2::XMLNode* child = node->FirstChild(); child != nullptr; child = child->NextSibling()) {
        pending.push_back(child);
      }
    }
  }

  void walk(const XMLElement* parent, FileScope& scope, int depth) {
    for (const XMLElement* e = parent->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      if (!enabled(e, scope)) continue;
      const std::string tag = e->Name();
      if (tag == "arg") {
        declareArg(e, scope);
      } else if (tag == "group") {
        const std::string saved = scope.ns;
        if (const char* ns = e->Attribute("ns")) scope.ns = resolve(e, scope, scope.ns, subst(ns, e, scope));
        walk(e, scope, depth);
        scope.ns = saved;
      } else if (tag == "include") {
        include(e, scope, depth);
      } else if (tag == "param") {
        param(e, scope, scope.ns);
      } else if (tag == "rosparam") {
        rosparam(e, scope, scope.ns);
      } else if (tag == "node") {
        node(e, scope);
      } else if (tag == "remap" || tag == "env" || tag == "machine" || tag == "test") {
        if (tag == "test") skipped_.push_back(attribute(e, "test_name", scope) + " (test)");
      } else {
        fail(e, scope, "<" + tag + "> is not a roslaunch element (roslaunch knows launch, arg, group, include, param, "
                                   "rosparam, node, remap, env, machine, test)");
      }
    }
  }

  bool enabled(const XMLElement* e, const FileScope& scope) {
    const char* if_text = e->Attribute("if");
    const char* unless_text = e->Attribute("unless");
    if (if_text != nullptr && unless_text != nullptr) fail(e, scope, "has both 'if' and 'unless'; keep one");
    const char* raw = if_text != nullptr ? if_text : unless_text;
    if (raw == nullptr) return true;
    const std::string text = subst(raw, e, scope);
    bool value = false;
    if (!truthValue(text, value)) {
      fail(e, scope, fmt::format("{}=\"{}\" gives '{}', which is neither true/1 nor false/0",
                                 if_text != nullptr ? "if" : "unless", raw, text));
    }
    return if_text != nullptr ? value : !value;
  }

  void declareArg(const XMLElement* e, FileScope& scope) {
    const std::string name = required(e, "name", scope);
    const char* value = e->Attribute("value");
    const char* fallback = e->Attribute("default");
    if (value != nullptr && fallback != nullptr) fail(e, scope, "arg '" + name + "' has both value= and default=");
    if (const auto earlier = scope.arg_lines.find(name); earlier != scope.arg_lines.end()) {
      fail(e, scope, "arg '" + name + "' has already been declared (at line " + std::to_string(earlier->second) +
                         "), as roslaunch says too; keep one <arg name=\"" + name + "\">");
    }
    scope.arg_lines[name] = e->GetLineNum();
    const auto passed = scope.passed.find(name);
    if (value != nullptr) {
      if (passed != scope.passed.end()) {
        fail(e, scope, "arg '" + name + "' is set here with value= and cannot be passed in; use default= to allow it");
      }
      scope.args[name] = subst(value, e, scope);
    } else if (passed != scope.passed.end()) {
      scope.args[name] = passed->second;
      scope.used.insert(name);
    } else if (fallback != nullptr) {
      scope.args[name] = subst(fallback, e, scope);
    } else {
      fail(e, scope, "arg '" + name + "' has no default and was not passed; pass " + name + ":=value");
    }
  }

  void include(const XMLElement* e, FileScope& scope, int depth) {
    const std::string raw = required(e, "file", scope);
    std::map<std::string, std::string> passed;
    std::map<std::string, int> passed_lines;
    for (const XMLElement* a = e->FirstChildElement("arg"); a != nullptr; a = a->NextSiblingElement("arg")) {
      if (!enabled(a, scope)) continue;
      const std::string name = required(a, "name", scope);
      const char* value = a->Attribute("value");
      if (value == nullptr) fail(a, scope, "<arg name=\"" + name + "\"> in an <include> needs value=");
      // roslaunch declares an <include>'s <arg>s in the included file's
      // context: the same name twice is its "arg 'x' has already been declared".
      if (const auto earlier = passed_lines.find(name); earlier != passed_lines.end()) {
        fail(a, scope, "arg '" + name + "' has already been declared in this <include> (at line " +
                           std::to_string(earlier->second) + "), as roslaunch says too; pass it once");
      }
      passed_lines[name] = a->GetLineNum();
      passed[name] = subst(value, a, scope);
    }
    // Gazebo's own world launch files (empty_world.launch and those built on
    // it): servoloop's world is that empty world, with its ground plane.
    if (raw.find("$(find gazebo_ros)") != std::string::npos) {
      world_.ground_plane = true;
      const auto world_name = passed.find("world_name");
      if (world_name != passed.end() && world_name->second.find("empty.world") == std::string::npos) {
        // An SDFormat world file: read (its models come before the spawned
        // robots); Gazebo's own worlds/ names it does not have.
        const fs::path world_file = resolvePath(world_name->second, scope);
        std::error_code ec;
        if (fs::is_regular_file(world_file, ec)) {
          world_file_ = world_file;
        } else {
          logger().warn("{}: Gazebo world '{}' is not a file servoloop finds (looked for {}); the robots are spawned "
                        "into an empty world (a ground plane and gravity)",
                        place(e, scope).text(), world_name->second, world_file.string());
        }
      }
      return;
    }
    FileScope inner;
    inner.file = resolvePath(subst(raw, e, scope), scope);
    inner.ns = scope.ns;
    if (const char* ns = e->Attribute("ns")) inner.ns = resolve(e, scope, scope.ns, subst(ns, e, scope));
    bool pass_all = false;
    if (const char* all = e->Attribute("pass_all_args")) truthValue(subst(all, e, scope), pass_all);
    inner.passed = pass_all ? scope.args : std::map<std::string, std::string>{};
    for (auto& [name, value] : passed) inner.passed[name] = value;
    if (pass_all) {
      // Passed along whether or not the included file declares them.
      for (const auto& [name, value] : scope.args) {
        if (passed.count(name) == 0) inner.used.insert(name);
      }
    }
    try {
      readFile(inner, depth + 1);
    } catch (const ConfigError& error) {
      throw ConfigError(std::string(error.what()) + "; included at " + place(e, scope).text());
    }
  }

  void param(const XMLElement* e, FileScope& scope, const std::string& ns) {
    const std::string name = resolve(e, scope, ns, subst(required(e, "name", scope), e, scope));
    const char* value = e->Attribute("value");
    const char* textfile = e->Attribute("textfile");
    const char* command = e->Attribute("command");
    if ((value != nullptr) + (textfile != nullptr) + (command != nullptr) + (e->Attribute("binfile") != nullptr) != 1) {
      fail(e, scope, "param '" + name + "' needs exactly one of value=, textfile=, command=, binfile=");
    }
    if (value != nullptr) {
      setParameter(e, scope, name, subst(value, e, scope), e->Attribute("type"));
    } else if (textfile != nullptr) {
      descriptions_[name] = Description{resolvePath(subst(textfile, e, scope), scope), {}, ""};
    } else if (command != nullptr) {
      descriptions_[name] = commandDescription(e, scope, command);
    }
  }

  // `xacro FILE name:=value ...` (also `$(find xacro)/xacro`, `xacro.py`,
  // `rosrun xacro xacro`, with --inorder and other options) or `cat FILE`.
  Description commandDescription(const XMLElement* e, FileScope& scope, std::string raw) {
    const std::string find_xacro = "$(find xacro)/";
    for (auto at = raw.find(find_xacro); at != std::string::npos; at = raw.find(find_xacro)) {
      raw.erase(at, find_xacro.size());
    }
    const std::vector<std::string> words = splitWords(subst(raw, e, scope));
    Description description;
    std::size_t i = 0;
    const auto isXacro = [](const std::string& w) {
      const std::string base = fs::path(w).filename().string();
      return base == "xacro" || base == "xacro.py";
    };
    if (!words.empty() && words[0] == "rosrun" && words.size() > 2 && words[1] == "xacro") i = 2;
    if (i < words.size() && (isXacro(words[i]) || words[i] == "cat")) {
      const bool cat = words[i] == "cat";
      for (++i; i < words.size(); ++i) {
        const std::string& w = words[i];
        if (w == "-o") {
          ++i;
        } else if (!w.empty() && w[0] == '-') {
          continue;
        } else if (!cat && w.find(":=") != std::string::npos) {
          description.xacro_args.insert(parseXacroArg(w));
        } else if (description.file.empty()) {
          description.file = resolvePath(w, scope);
        }
      }
      if (!description.file.empty()) return description;
    }
    description.unusable = "command=\"" + raw + "\" (" + place(e, scope).text() +
                           ") is not `xacro FILE [name:=value ...]` or `cat FILE`, the commands servoloop runs for a "
                           "robot description";
    return description;
  }

  void setParameter(const XMLElement* e, FileScope& scope, const std::string& name, const std::string& text,
                    const char* type) {
    YAML::Emitter out;
    out << YAML::BeginMap << YAML::Key << fs::path(name).filename().string() << YAML::Value;
    const std::string kind = type != nullptr ? type : "";
    // roslaunch strips a value before it converts it: value="  1.0  " is the
    // double 1.0, not a string (which a double parameter would not read).
    const auto first = text.find_first_not_of(" \t\r\n");
    const std::string trimmed =
        first == std::string::npos ? std::string() : text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
    std::string lower = trimmed;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    char* end = nullptr;
    const bool number =
        !trimmed.empty() && (std::strtod(trimmed.c_str(), &end), end == trimmed.c_str() + trimmed.size());
    bool truth = false;
    if (kind == "str" || kind == "string") {
      out << YAML::DoubleQuoted << text;
    } else if (kind == "yaml") {
      try {
        out << YAML::Load(text);
      } catch (const YAML::Exception& error) {
        fail(e, scope, "param '" + name + "': type=\"yaml\" but the value is not YAML: " + error.msg);
      }
    } else if (kind == "bool" || kind == "boolean") {
      if (!truthValue(trimmed, truth)) fail(e, scope, "param '" + name + "': '" + text + "' is not true or false");
      out << truth;
    } else if (kind.empty() && (lower == "true" || lower == "false")) {
      out << (lower == "true");  // roslaunch reads these as booleans
    } else if ((kind.empty() || kind == "int" || kind == "double") && number) {
      out << trimmed;  // an integer or a double, as its text says
    } else if (kind.empty()) {
      out << YAML::DoubleQuoted << text;
    } else {
      fail(e, scope, fmt::format("param '{}': value '{}' is not of type '{}' (roslaunch's types: str, int, double, "
                                 "bool, yaml)", name, text, kind));
    }
    out << YAML::EndMap;
    const std::string parent = fs::path(name).parent_path().string();
    params_.push_back(ParameterFile{{}, parent.empty() ? "/" : parent, out.c_str(), place(e, scope).text()});
  }

  void rosparam(const XMLElement* e, FileScope& scope, const std::string& ns) {
    const std::string command = e->Attribute("command") ? subst(e->Attribute("command"), e, scope) : "load";
    if (command != "load") {
      logger().warn("{}: <rosparam command=\"{}\"> is not run: servoloop loads parameters only",
                    place(e, scope).text(), command);
      return;
    }
    std::string target = ns;
    if (const char* sub = e->Attribute("ns")) target = resolve(e, scope, target, subst(sub, e, scope));
    if (const char* name = e->Attribute("param")) target = resolve(e, scope, target, subst(name, e, scope));
    bool substitute = false;
    if (const char* flag = e->Attribute("subst_value")) truthValue(flag, substitute);
    if (const char* file = e->Attribute("file")) {
      const fs::path path = resolvePath(subst(file, e, scope), scope);
      if (!substitute) {
        params_.push_back(ParameterFile{path, target, "", ""});
        return;
      }
      // roslaunch substitutes $(arg ...) and the others in the file's text
      // before reading it as YAML (franka_gazebo's controller YAML names its
      // joints $(arg arm_id)_joint1).
      std::string yaml;
      try {
        yaml = readTextFile(path, "rosparam file");
      } catch (const ConfigError& error) {
        fail(e, scope, error.what());
      }
      params_.push_back(ParameterFile{{}, target, subst(yaml, e, scope), path.string()});
      return;
    }
    std::string text = e->GetText() != nullptr ? e->GetText() : "";
    if (substitute) text = subst(text, e, scope);
    if (e->Attribute("param") != nullptr) {
      // The text is the value of that one parameter.
      const std::string parent = fs::path(target).parent_path().string();
      text = fs::path(target).filename().string() + ":\n" + indent(text);
      target = parent.empty() ? "/" : parent;
    }
    params_.push_back(ParameterFile{{}, target, text, place(e, scope).text()});
  }

  static std::string indent(const std::string& text) {
    std::string out = "  ";
    for (char c : text) {
      out += c;
      if (c == '\n') out += "  ";
    }
    return out;
  }

  void node(const XMLElement* e, FileScope& scope) {
    const std::string pkg = attribute(e, "pkg", scope);
    const std::string type = attribute(e, "type", scope);
    const std::string name = attribute(e, "name", scope);
    std::string ns = scope.ns;
    if (const char* sub = e->Attribute("ns")) ns = resolve(e, scope, ns, subst(sub, e, scope));
    const std::vector<std::string> args = splitWords(e->Attribute("args") ? subst(e->Attribute("args"), e, scope) : "");
    // A node's own <param>/<rosparam> are its private parameters.
    const std::string private_ns = resolve(e, scope, ns, name.empty() ? "unnamed" : name);
    for (const XMLElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      if (!enabled(c, scope)) continue;
      const std::string tag = c->Name();
      if (tag == "param") param(c, scope, private_ns);
      if (tag == "rosparam") rosparam(c, scope, private_ns);
    }
    if (pkg == "gazebo_ros" && (type == "spawn_model" || type == "spawn_model.py")) {
      spawnModel(e, scope, ns, args);
    } else if (pkg == "controller_manager" && (type == "spawner" || type == "spawner.py" || type == "controller_manager")) {
      spawner(e, scope, ns, args, type == "controller_manager");
    } else {
      skipped_.push_back((name.empty() ? "unnamed" : name) + " (" + pkg + "/" + type + ")");
    }
  }

  void spawnModel(const XMLElement* e, FileScope& scope, const std::string& ns, const std::vector<std::string>& args) {
    SpawnModel spawn;
    spawn.place = place(e, scope);
    spawn.robot_namespace = ns;
    static const std::map<std::string, int> kPose{{"-x", 0}, {"-y", 1}, {"-z", 2}, {"-R", 3}, {"-P", 4}, {"-Y", 5}};
    const auto value = [&](std::size_t& i) -> std::string {
      if (i + 1 >= args.size()) fail(e, scope, "spawn_model option " + args[i] + " needs a value");
      return args[++i];
    };
    const auto number = [&](const std::string& option, const std::string& text) {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
        fail(e, scope, "spawn_model " + option + " " + text + ": not a number");
      }
      return v;
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& option = args[i];
      if (option == "-urdf" || option == "-unpause" || option == "-wait" || option == "-gazebo_namespace") {
        if (option == "-gazebo_namespace") value(i);
      } else if (option == "-param") {
        spawn.description_param = resolve(e, scope, ns, value(i));
      } else if (option == "-file") {
        spawn.file = resolvePath(value(i), scope);
      } else if (option == "-model") {
        spawn.model = value(i);
      } else if (option == "-robot_namespace") {
        spawn.robot_namespace = resolve(e, scope, "/", value(i));
      } else if (kPose.count(option) > 0) {
        spawn.pose[static_cast<std::size_t>(kPose.at(option))] = number(option, value(i));
        spawn.pose_given = true;
      } else if (option == "-J") {
        const std::string joint = value(i);
        const std::string position = value(i);
        number("-J " + joint, position);
        spawn.initial_positions[joint] = position;
      } else if (option == "-sdf" || option == "-database") {
        fail(e, scope, "spawn_model " + option + ": servoloop spawns URDF robots only (-urdf with -param or -file)");
      } else if (option == "-reference_frame" || option == "-package_to_model") {
        if (option == "-reference_frame") value(i);
        logger().warn("{}: spawn_model {} is ignored: poses are in the world frame", spawn.place.text(), option);
      } else {
        fail(e, scope, "spawn_model: unknown option '" + option +
                           "' (servoloop reads -urdf, -param, -file, -model, -x -y -z -R -P -Y, -J, -robot_namespace, "
                           "-unpause, -wait)");
      }
    }
    if (spawn.model.empty()) fail(e, scope, "spawn_model needs -model NAME");
    if (spawn.description_param.empty() == spawn.file.empty()) {
      fail(e, scope, "spawn_model needs one of -param NAME (a <param> holding the URDF) or -file FILE");
    }
    spawns_.push_back(std::move(spawn));
  }

  void spawner(const XMLElement* e, FileScope& scope, const std::string& ns, const std::vector<std::string>& args,
               bool controller_manager_form) {
    Spawner spawner;
    spawner.place = place(e, scope);
    spawner.ns = ns;
    std::size_t i = 0;
    if (controller_manager_form) {
      const std::string verb = args.empty() ? "" : args[0];
      if (verb != "spawn" && verb != "load") {
        fail(e, scope, "controller_manager args=\"" + verb +
                           " ...\": servoloop runs 'spawn' and 'load' (or use the spawner node)");
      }
      spawner.stopped = verb == "load";
      i = 1;
    }
    for (; i < args.size(); ++i) {
      const std::string& word = args[i];
      if (word == "--stopped") {
        spawner.stopped = true;
      } else if (word == "--namespace") {
        if (i + 1 >= args.size()) fail(e, scope, "spawner --namespace needs a value");
        spawner.ns = resolve(e, scope, "/", args[++i]);
      } else if (word == "--shutdown-timeout" || word == "--timeout" || word == "-t" || word == "--wait-for") {
        // These take a value: franka_gazebo's "--wait-for initialized" waits for
        // its simulation to report the robot initialized, which it is here when
        // controllers load.
        ++i;
      } else if (word.rfind("--namespace=", 0) == 0) {
        spawner.ns = resolve(e, scope, "/", word.substr(12));
      } else if (word.rfind("--", 0) == 0) {
        continue;  // other spawner options (--shutdown-timeout=3, --wait-for=...) change nothing here
      } else {
        spawner.controllers.push_back(word);
      }
    }
    spawners_.push_back(std::move(spawner));
  }

  // ----- putting the LaunchFile together -----

  LaunchFile assemble(const fs::path& source) {
    LaunchFile launch;
    launch.source = source;
    launch.world = world_;
    if (!world_file_.empty()) addSdfWorld(world_file_, launch.world, launch.robots);
    std::vector<std::string> namespaces;
    for (const SpawnModel& spawn : spawns_) {
      RobotSpec robot;
      robot.model = spawn.model;
      robot.robot_namespace = spawn.robot_namespace;
      if (!spawn.file.empty()) {
        robot.urdf = spawn.file;
      } else {
        const auto it = descriptions_.find(spawn.description_param);
        if (it == descriptions_.end()) {
          throw ConfigError(fmt::format("{}: spawn_model -param {}: no <param name=\"{}\" textfile=... or "
                                        "command=\"xacro ...\"> sets it before; set the robot description there",
                                        spawn.place.text(), spawn.description_param, spawn.description_param));
        }
        if (!it->second.unusable.empty()) {
          throw ConfigError(spawn.place.text() + ": spawn_model -param " + spawn.description_param + ": " +
                            it->second.unusable);
        }
        robot.urdf = it->second.file;
        robot.xacro_args = it->second.xacro_args;
      }
      std::error_code ec;
      if (!fs::exists(robot.urdf, ec)) {
        throw ConfigError(spawn.place.text() + ": the robot description " + robot.urdf.string() +
                          " does not exist; fix the path");
      }
      if (spawn.pose_given) robot.pose = spawn.pose;
      const std::string xml = readRobotDescription(robot.urdf, robot.xacro_args);
      const std::string ns = resolveRobotNamespace(xml, robot.urdf.string(), robot.robot_namespace, robot.model);
      namespaces.push_back(ns);
      if (!spawn.initial_positions.empty()) {
        YAML::Emitter out;
        out << YAML::BeginMap << YAML::Key << "initial_positions" << YAML::Value << YAML::BeginMap;
        for (const auto& [joint, position] : spawn.initial_positions) out << YAML::Key << joint << YAML::Value << position;
        out << YAML::EndMap << YAML::EndMap;
        robot.params.push_back(ParameterFile{{}, params::resolveName(ns, "sim"), out.c_str(), spawn.place.text()});
      }
      launch.robots.push_back(std::move(robot));
    }
    for (const Spawner& spawner : spawners_) {
      const auto it = std::find(namespaces.begin(), namespaces.end(), spawner.ns);
      if (it == namespaces.end()) {
        throw ConfigError(fmt::format(
            "{}: the controller spawner in namespace {} has no robot there (robots spawned: {}); put the spawner "
            "in the robot's namespace (ns=\"...\" or <group ns>) or give the robot that namespace",
            spawner.place.text(), spawner.ns, namespaces.empty() ? "none" : fmt::format("{}", fmt::join(namespaces, ", "))));
      }
      RobotSpec& robot = launch.robots[static_cast<std::size_t>(it - namespaces.begin())];
      auto& list = spawner.stopped ? robot.stopped_controllers : robot.controllers;
      list.insert(list.end(), spawner.controllers.begin(), spawner.controllers.end());
    }
    // roslaunch sets every parameter before it starts any node.
    if (!launch.robots.empty()) {
      auto& first = launch.robots.front().params;
      first.insert(first.begin(), params_.begin(), params_.end());
    }
    if (!skipped_.empty()) {
      logger().warn("{}: not run (servoloop runs the simulation, the robots and their controllers): {}", source.string(),
                    fmt::join(skipped_, ", "));
    }
    return launch;
  }

  // ----- substitutions, names, paths -----

  std::string subst(const std::string& text, const XMLElement* e, const FileScope& scope) {
    // $(eval) is a whole attribute (roslaunch's rule): a Python expression
    // over the arguments, which may hold parentheses of its own.
    if (text.rfind("$(eval ", 0) == 0 && text.size() > 8 && text.back() == ')') {
      try {
        return evaluatePythonExpression(text.substr(7, text.size() - 8), scope.args);
      } catch (const ConfigError& error) {
        fail(e, scope, error.what());
      }
    }
    std::string out;
    std::size_t i = 0;
    while (i < text.size()) {
      const auto start = text.find("$(", i);
      if (start == std::string::npos) {
        out += text.substr(i);
        break;
      }
      out += text.substr(i, start - i);
      const auto end = text.find(')', start);
      if (end == std::string::npos) fail(e, scope, "'" + text + "': '$(' without a closing ')'");
      const std::string inside = text.substr(start + 2, end - start - 2);
      const auto space = inside.find(' ');
      const std::string command = inside.substr(0, space);
      const std::string rest = space == std::string::npos ? "" : inside.substr(space + 1);
      out += substitution(command, rest, e, scope);
      i = end + 1;
    }
    return out;
  }

  std::string substitution(const std::string& command, const std::string& rest, const XMLElement* e,
                           const FileScope& scope) {
    if (command == "arg") {
      const auto it = scope.args.find(rest);
      if (it == scope.args.end()) {
        fail(e, scope, "$(arg " + rest + "): no <arg name=\"" + rest + "\"> is declared before this line in " +
                           scope.file.filename().string());
      }
      return it->second;
    }
    if (command == "find") {
      try {
        return findPackage(rest, scope.file.parent_path(), scope.file.string()).string();
      } catch (const ConfigError& error) {
        fail(e, scope, "$(find " + rest + "): " + error.what());
      }
    }
    if (command == "env" || command == "optenv") {
      const auto split = rest.find(' ');
      const std::string variable = rest.substr(0, split);
      if (const char* value = std::getenv(variable.c_str())) return value;
      if (command == "optenv") return split == std::string::npos ? "" : rest.substr(split + 1);
      fail(e, scope, "$(env " + variable + "): the environment variable is not set; set it or use $(optenv)");
    }
    if (command == "dirname") return scope.file.parent_path().string();
    if (command == "anon") return rest + "_servoloop";
    if (command == "eval") fail(e, scope, "$(eval ...) must be the whole attribute value, as roslaunch requires");
    fail(e, scope, "$(" + command + " ...) is not a substitution servoloop knows (it knows $(arg), $(find), $(env), "
                                    "$(optenv), $(dirname), $(anon), $(eval))");
  }

  std::string resolve(const XMLElement* e, const FileScope& scope, const std::string& ns, const std::string& name) {
    try {
      return params::resolveName(ns, name);
    } catch (const Error& error) {
      fail(e, scope, "name '" + name + "': " + error.what());
    }
  }

  fs::path resolvePath(const std::string& text, const FileScope& scope) const {
    const fs::path path(text);
    return (path.is_absolute() ? path : scope.file.parent_path() / path).lexically_normal();
  }

  std::string attribute(const XMLElement* e, const char* name, const FileScope& scope) {
    const char* value = e->Attribute(name);
    return value != nullptr ? subst(value, e, scope) : "";
  }

  std::string required(const XMLElement* e, const char* name, const FileScope& scope) {
    const char* value = e->Attribute(name);
    if (value == nullptr) fail(e, scope, std::string("needs the attribute ") + name + "=");
    return value;
  }

  static Place place(const XMLElement* e, const FileScope& scope) { return {scope.file.string(), e->GetLineNum()}; }

  [[noreturn]] static void fail(const XMLElement* e, const FileScope& scope, const std::string& message) {
    throw ConfigError(place(e, scope).text() + ": <" + e->Name() + ">: " + message);
  }

  std::map<std::string, std::string> command_line_args_;
  std::vector<std::unique_ptr<tinyxml2::XMLDocument>> documents_;
  std::map<std::string, Description> descriptions_;
  std::vector<ParameterFile> params_;
  std::vector<SpawnModel> spawns_;
  std::vector<Spawner> spawners_;
  std::vector<std::string> skipped_;
  WorldSettings world_;
  fs::path world_file_;  // gazebo_ros's world_name, when it is a file
};

}  // namespace

bool isRoslaunchPath(const fs::path& path) { return path.extension() == ".launch" || path.extension() == ".xml"; }

LaunchFile loadRoslaunchFile(const fs::path& path, const std::map<std::string, std::string>& args) {
  return Reader(args).read(path);
}

}  // namespace servoloop::node
