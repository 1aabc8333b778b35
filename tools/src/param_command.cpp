// `servoloop param load|get|set|dump|list`: rosparam for a running node's
// parameter store. Names resolve as in ROS (relative ones under --namespace or
// "/"); the node is the one whose namespace prefixes the name, or --namespace,
// or the only one running.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/params/parameter_store.hpp"

namespace servoloop::cli {
namespace {


struct ParamOptions {
  std::string ns;  // --namespace: which node
  std::string file;
  std::string name;  // parameter name or namespace argument
  std::string value;
  std::string output;
  bool json = false;
};

void emitYaml(YAML::Emitter& out, const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::object:
      out << YAML::BeginMap;
      for (const auto& [key, item] : value.items()) {
        out << YAML::Key << key << YAML::Value;
        emitYaml(out, item);
      }
      out << YAML::EndMap;
      break;
    case nlohmann::json::value_t::array:
      out << YAML::Flow << YAML::BeginSeq;
      for (const auto& item : value) emitYaml(out, item);
      out << YAML::EndSeq;
      break;
    case nlohmann::json::value_t::string:
      out << value.get<std::string>();
      break;
    case nlohmann::json::value_t::null:
      out << YAML::Null;
      break;
    default:
      out << value.dump();  // numbers and booleans: JSON text is valid YAML
      break;
  }
}

// A parameter namespace argument: absolute, default "/".
std::string namespaceArgument(const ParamOptions& options) {
  if (options.name.empty()) return "/";
  return resolveName(options.ns, options.name);
}

void runLoad(const ParamOptions& options) {
  const std::string file = existingFileArgument(options.file, "parameter file");
  const std::string ns = namespaceArgument(options);
  servoloop::ipc::IpcClient client = connectForName(ns == "/" ? "/" : ns + "/", options.ns);
  client.call("param.load", {{"file", file}, {"namespace", ns}});
  std::cout << "Loaded " << file << " into " << ns << "\n";
}

void runGet(const ParamOptions& options) {
  const std::string name = resolveName(options.ns, options.name);
  servoloop::ipc::IpcClient client = connectForName(name, options.ns);
  const auto value = client.call("param.get", {{"name", name}}).value("value", nlohmann::json());
  if (options.json) {
    std::cout << value.dump() << "\n";
    return;
  }
  YAML::Emitter out;
  emitYaml(out, value);
  std::cout << out.c_str() << "\n";
}

void runSet(const ParamOptions& options) {
  // Checked as given, before it is resolved under --namespace: "" would
  // become the namespace itself (and replace all of it), "~x" would become a
  // name no one can read back.
  try {
    params::checkParameterName(options.name);
  } catch (const Error& e) {
    throw ConfigError(std::string("param set: ") + e.what());
  }
  const std::string name = resolveName(options.ns, options.name);
  servoloop::ipc::IpcClient client = connectForName(name, options.ns);
  // Sent as text: the node types it as YAML would (1 → int, 1.0 → double,
  // "1" → string), exactly like a value in a parameter file.
  client.call("param.set", {{"name", name}, {"value", options.value}});
}

void runDump(const ParamOptions& options) {
  const std::string ns = namespaceArgument(options);
  servoloop::ipc::IpcClient client = connectForName(ns == "/" ? "/" : ns + "/", options.ns);
  const std::string yaml = client.call("param.dump", {{"namespace", ns}}).value("yaml", "");
  if (options.output.empty()) {
    std::cout << yaml << (yaml.empty() || yaml.back() == '\n' ? "" : "\n");
    return;
  }
  std::ofstream out(options.output);
  if (!out) throw Error("cannot write '" + options.output + "': check the folder exists");
  out << yaml << (yaml.empty() || yaml.back() == '\n' ? "" : "\n");
  if (!out.flush()) throw Error("cannot write '" + options.output + "'");
}

void runList(const ParamOptions& options) {
  const std::string ns = namespaceArgument(options);
  servoloop::ipc::IpcClient client = connectForName(ns == "/" ? "/" : ns + "/", options.ns);
  const auto names = client.call("param.list", {{"namespace", ns}})
                         .value("names", nlohmann::json::array());
  if (options.json) {
    std::cout << names.dump(2) << "\n";
    return;
  }
  for (const auto& name : names) std::cout << (name.is_string() ? name.get<std::string>() : name.dump()) << "\n";
}

void addParamCommands(CLI::App& root) {
  CLI::App& param = commandGroup(root, "param", "Load, get, set, dump and list a node's parameters");

  {
    auto options = std::make_shared<ParamOptions>();
    CLI::App* load =
        param.add_subcommand("load", "Load a ros_control-style YAML file into the parameters");
    addNamespaceOption(*load, options->ns);
    load->add_option("file", options->file, "YAML file")->required()->type_name("FILE");
    load->add_option("param_namespace", options->name, "Namespace to load under (default /)")
        ->type_name("NS");
    load->callback([options] { runLoad(*options); });
  }
  {
    auto options = std::make_shared<ParamOptions>();
    CLI::App* get = param.add_subcommand("get", "Print a parameter (a value or a whole namespace)");
    addNamespaceOption(*get, options->ns);
    get->add_option("name", options->name, "Parameter name")->required();
    get->add_flag("--json", options->json, "Print the value as JSON");
    get->callback([options] { runGet(*options); });
  }
  {
    auto options = std::make_shared<ParamOptions>();
    CLI::App* set = param.add_subcommand("set", "Set a parameter; VALUE is typed as in YAML");
    addNamespaceOption(*set, options->ns);
    set->add_option("name", options->name, "Parameter name")->required();
    set->add_option("value", options->value, "Value, e.g. 10.0, 3, true, [1, 2], {p: 1.0}")
        ->required();
    set->callback([options] { runSet(*options); });
  }
  {
    auto options = std::make_shared<ParamOptions>();
    CLI::App* dump = param.add_subcommand("dump", "Print (or write) parameters as YAML");
    addNamespaceOption(*dump, options->ns);
    dump->add_option("param_namespace", options->name, "Namespace to dump (default /)")
        ->type_name("NS");
    dump->add_option("-o,--output", options->output, "Write to this file instead")
        ->type_name("FILE");
    dump->callback([options] { runDump(*options); });
  }
  {
    auto options = std::make_shared<ParamOptions>();
    CLI::App* list = param.add_subcommand("list", "List parameter names");
    addNamespaceOption(*list, options->ns);
    list->add_option("param_namespace", options->name, "Namespace to list (default /)")
        ->type_name("NS");
    list->add_flag("--json", options->json, "Print a JSON array of names");
    list->callback([options] { runList(*options); });
  }
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(50, servoloop::cli::addParamCommands)
