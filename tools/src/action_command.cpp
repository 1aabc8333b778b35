// `servoloop action send|list`: actionlib's command-line client for the
// actions a running node's controllers serve (a joint trajectory
// controller's follow_joint_trajectory). `send` prints the goal's feedback as
// it comes and its result at the end; Ctrl-C cancels the goal (and waits for
// it to end, at most kCancelGrace); the exit status says how it ended: 0
// succeeded, 1 aborted or rejected, 2 canceled or preempted.
//
// SIGINT/SIGTERM set a flag (installStopSignalHandlers); once it is set,
// sleepUnlessStopped() returns at once, so the wait after a cancel sleeps
// plainly (it used to loop on sleepUnlessStopped and spin a core, forever
// when the goal never ended).
#include <chrono>
#include <iostream>
#include <thread>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/node/message_json.hpp"

namespace servoloop::cli {
namespace {

using Clock = std::chrono::steady_clock;

// How long a canceled goal may take to end before `action send` gives up on
// it (a controller stops its joints within stop_trajectory_duration).
constexpr std::chrono::seconds kCancelGrace{5};

struct ActionOptions {
  std::string ns;
  std::string name;
  std::string type;
  std::string goal;
  bool json = false;
  double poll_s = 0.05;
};

// Lines indented by `indent` spaces.
std::string indented(const std::string& text, int indent) {
  std::string out;
  std::string pad(static_cast<std::size_t>(indent), ' ');
  bool line_start = true;
  for (char c : text) {
    if (line_start && c != '\n') out += pad;
    out += c;
    line_start = c == '\n';
  }
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

// Feedback of a control_msgs/FollowJointTrajectory goal reads as the
// controller's state message; others as one "field: value" line per field.
std::string feedbackText(const std::string& action_type, const nlohmann::json& feedback) {
  if (action_type == "control_msgs/FollowJointTrajectory") {
    return servoloop::node::messageToText("control_msgs/JointTrajectoryControllerState", feedback);
  }
  if (!feedback.is_object()) return feedback.dump();
  std::string text;
  for (const auto& [key, value] : feedback.items()) text += key + ": " + value.dump() + "\n";
  return text;
}

int exitStatusOf(const std::string& state) {
  if (state == "SUCCEEDED") return 0;
  if (state == "CANCELED" || state == "PREEMPTED") return 2;
  return 1;
}

void runSend(const ActionOptions& options) {
  const std::string name = resolveName(options.ns, options.name);
  if (options.goal.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw Error("GOAL is empty: give the " + options.type + " goal as YAML or JSON, e.g. "
                "\"{trajectory: {joint_names: [joint1], points: [{positions: [1.0], time_from_start: 2.0}]}}\"");
  }
  const nlohmann::json goal = servoloop::node::parseMessageText(options.goal, "GOAL");
  servoloop::ipc::IpcClient client = connectForName(name, options.ns);
  const nlohmann::json sent = client.call("action.send", {{"name", name}, {"type", options.type}, {"goal", goal}});
  const std::uint64_t id = sent.at("goal_id").get<std::uint64_t>();
  installStopSignalHandlers();
  bool cancel_sent = false;
  Clock::time_point cancel_deadline{};
  std::string last_feedback;
  nlohmann::json status;
  while (true) {
    if (stopRequested() && !cancel_sent) {
      cancel_sent = true;
      cancel_deadline = Clock::now() + kCancelGrace;
      try {
        client.call("action.cancel", {{"goal_id", id}});
      } catch (const Error&) {
        // The goal ended (and was read) meanwhile: its status below says how.
      }
      if (!options.json) std::cerr << "canceling the goal\n";
    }
    status = client.call("action.status", {{"goal_id", id}});
    const nlohmann::json& feedback = status.value("feedback", nlohmann::json());
    if (!feedback.is_null() && feedback.dump() != last_feedback) {
      last_feedback = feedback.dump();
      if (options.json) {
        std::cout << nlohmann::json{{"feedback", feedback}}.dump() << std::endl;
      } else {
        std::cout << "feedback:\n"
                  << indented(feedbackText(options.type, feedback), 2)
                  << "---" << std::endl;
      }
    }
    if (status.contains("result")) break;
    if (cancel_sent) {
      if (Clock::now() >= cancel_deadline) {
        const std::string state = status.value("state", "");
        if (options.json) {
          std::cout << nlohmann::json{{"state", state}, {"error", "the goal did not end after its cancel"}}.dump()
                    << std::endl;
        } else {
          std::cerr << "the goal is still " << state << " " << kCancelGrace.count()
                    << " s after its cancel; not waiting for it any longer (the controller may be stopped or "
                       "stuck: see `servoloop control list` and the node's log)\n";
        }
        throw CliExit{2};
      }
      // The stop flag stays set, so sleepUnlessStopped() would return at
      // once: sleep plainly while the cancel takes effect.
      std::this_thread::sleep_for(std::chrono::duration<double>(options.poll_s));
    } else {
      sleepUnlessStopped(options.poll_s);
    }
  }
  const std::string state = status.value("state", "");
  const nlohmann::json& result = status["result"];
  const std::string text = status.value("text", "");
  if (options.json) {
    nlohmann::json out{{"state", state}, {"result", result}};
    if (!text.empty()) out["text"] = text;
    std::cout << out.dump() << std::endl;
  } else {
    std::cout << "result:\n";
    for (const auto& [key, value] : result.items()) {
      std::cout << "  " << key << ": " << value.dump() << "\n";
    }
    std::cout << "state: " << state << std::endl;
    if (!text.empty()) std::cout << "text: " << text << std::endl;
  }
  if (const int code = exitStatusOf(state); code != 0) throw CliExit{code};
}

void runList(const ActionOptions& options) {
  servoloop::ipc::IpcClient client = connectToRobotNode(options.ns);
  const nlohmann::json actions = client.call("action.list").value("actions", nlohmann::json::array());
  if (options.json) {
    std::cout << actions.dump(2) << "\n";
    return;
  }
  std::size_t width = 0;
  for (const auto& action : actions) width = std::max(width, action.value("name", "").size());
  for (const auto& action : actions) {
    const std::string action_name = action.value("name", "");
    std::cout << action_name << std::string(width - action_name.size() + 2, ' ') << action.value("type", "") << "\n";
  }
}

void addActionCommands(CLI::App& root) {
  CLI::App& action = commandGroup(root, "action", "Send goals to the actions a node's controllers serve (actionlib)");
  {
    auto options = std::make_shared<ActionOptions>();
    CLI::App* send = action.add_subcommand(
        "send",
        "Send a goal; print its feedback as it comes and its result at the end. Ctrl-C cancels the goal. "
        "Exit status: 0 succeeded, 1 aborted or rejected, 2 canceled or preempted");
    addNamespaceOption(*send, options->ns);
    send->add_option("name", options->name, "Action name, e.g. /arm/arm_controller/follow_joint_trajectory")
        ->required();
    send->add_option("type", options->type, "Action type, e.g. control_msgs/FollowJointTrajectory")->required();
    send->add_option("goal", options->goal, "The goal as YAML or JSON")->required();
    send->add_flag("--json", options->json, "One JSON object per line: {feedback} as it comes, then {state, result}");
    send->callback([options] { runSend(*options); });
  }
  {
    auto options = std::make_shared<ActionOptions>();
    CLI::App* list = action.add_subcommand("list", "List the actions a node serves, with their types");
    addNamespaceOption(*list, options->ns);
    list->add_flag("--json", options->json, "Print a JSON array of {name, type}");
    list->callback([options] { runList(*options); });
  }
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(45, servoloop::cli::addActionCommands)
