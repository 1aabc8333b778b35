// `servoloop topic pub|echo|list|hz`: rostopic for a running node's topic bus.
// A topic is served by the node whose robot namespace prefixes it (or the one
// chosen with --namespace, or the only node running); `list` without
// --namespace shows the topics of every running node.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "node_connection.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/realtime/messages.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct TopicOptions {
  std::string ns;
  std::string topic;
  std::string type;
  std::string value;
  double rate_hz = 0.0;
  int count = 0;  // 0: no limit
  bool json = false;
  std::size_t window = 1000;
};

// --- messages -----------------------------------------------------------------

// JSON with a space after ':' and ',' (the form CLI.md shows), keys in the
// order given.
std::string dumpSpaced(const nlohmann::ordered_json& value) {
  if (value.is_object()) {
    std::string text = "{";
    bool first = true;
    for (const auto& [key, item] : value.items()) {
      text += (first ? "" : ", ") + nlohmann::json(key).dump() + ": " + dumpSpaced(item);
      first = false;
    }
    return text + "}";
  }
  if (value.is_array()) {
    std::string text = "[";
    for (std::size_t i = 0; i < value.size(); ++i) {
      text += (i == 0 ? "" : ", ") + dumpSpaced(value[i]);
    }
    return text + "]";
  }
  return value.dump();
}

// `echo --json` line: a JointState as {"stamp", "name", "position", "velocity",
// "effort"} in that order; other types with their fields as the node sent them.
std::string echoJsonLine(const StreamMessage& message) {
  if (message.type == servoloop::sensor_msgs::JointState::kTypeName) {
    const auto state = servoloop::node::messageFromJson<servoloop::sensor_msgs::JointState>(message.msg);
    nlohmann::ordered_json line;
    line["stamp"] = message.msg.contains("stamp") ? state.stamp : message.stamp.value_or(0.0);
    line["name"] = state.name;
    line["position"] = state.position;
    line["velocity"] = state.velocity;
    line["effort"] = state.effort;
    return dumpSpaced(line);
  }
  return dumpSpaced(nlohmann::ordered_json::parse(message.msg.dump()));
}

std::string echoText(const StreamMessage& message) {
  std::string text = servoloop::node::isKnownMessageType(message.type)
                         ? servoloop::node::messageToText(message.type, message.msg)
                         : message.msg.dump();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

// --- commands -----------------------------------------------------------------

void runPub(const TopicOptions& options) {
  const std::string topic = resolveName(options.ns, options.topic);
  if (options.value.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw Error("VALUE is empty: give the " + options.type +
                " message, e.g. 1.0 or \"{data: 1.0}\" (\"{}\" publishes one with every field at its default)");
  }
  const auto msg = servoloop::node::normalizeMessage(options.type, servoloop::node::parseMessageText(options.value, "VALUE"));
  if (options.rate_hz < 0.0) throw Error("-r/--rate must be > 0 (messages per second)");
  if (options.count < 0) throw Error("-n/--count must be >= 0");
  servoloop::ipc::IpcClient client = connectForName(topic, options.ns);
  const nlohmann::json request{{"topic", topic}, {"type", options.type}, {"msg", msg}};

  if (options.rate_hz == 0.0) {
    const int count = std::max(options.count, 1);
    for (int i = 0; i < count; ++i) client.call("topic.pub", request);
    std::cout << "published " << count << " message" << (count == 1 ? "" : "s") << " to " << topic
              << "\n";
    return;
  }

  // Absolute deadlines, so the rate does not drift with the request time.
  installStopSignalHandlers();
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options.rate_hz));
  auto next = Clock::now();
  long published = 0;
  while (!stopRequested() && (options.count == 0 || published < options.count)) {
    client.call("topic.pub", request);
    ++published;
    next += period;
    const double wait_s = std::chrono::duration<double>(next - Clock::now()).count();
    if (wait_s > 0.0) sleepUnlessStopped(wait_s);
    if (Clock::now() > next + period) next = Clock::now();  // fell behind: do not burst
  }
  std::cout << "published " << published << " messages to " << topic << "\n";
}

// Subscribes `client` to `topic` and hands each message to `on_message` until
// it returns false, a stop is requested, or the node goes away.
template <class OnMessage>
void forEachMessage(servoloop::ipc::IpcClient& client, const std::string& topic, OnMessage on_message) {
  installStopSignalHandlers();
  client.call("topic.subscribe", {{"topic", topic}});
  while (!stopRequested()) {
    const auto stream = client.readStream(0.1);
    if (!stream) continue;
    if (stream->value("stream", "") != topic) continue;
    if (!on_message(parseStreamMessage(*stream))) break;
  }
  try {
    client.call("topic.unsubscribe", {{"topic", topic}}, 1.0);
  } catch (const std::exception&) {
    // The connection closes right after; the node drops the subscription then.
  }
}

void runEcho(const TopicOptions& options) {
  if (options.count < 0) throw Error("-n/--count must be >= 0");
  const std::string topic = resolveName(options.ns, options.topic);
  servoloop::ipc::IpcClient client = connectForName(topic, options.ns);
  int received = 0;
  forEachMessage(client, topic, [&](const StreamMessage& message) {
    if (options.json) {
      std::cout << echoJsonLine(message) << std::endl;
    } else {
      std::cout << echoText(message) << "\n---" << std::endl;
    }
    ++received;
    return options.count == 0 || received < options.count;
  });
}

// One node's topics, each tagged with the node ({name, type, publishers,
// subscribers, node}).
nlohmann::json nodeTopics(servoloop::ipc::IpcClient& client, const std::string& node_name) {
  nlohmann::json topics = client.call("topic.list").value("topics", nlohmann::json::array());
  for (auto& topic : topics) topic["node"] = node_name;
  return topics;
}

// With --namespace: that node's topics. Without: every running node's, merged
// in node order (as rostopic list shows every topic of the ROS graph). A
// world's socket with no robot yet has no topics and is left out; a node that
// goes away while it is asked is skipped. Fails only when no node answered.
nlohmann::json listTopics(const std::string& ns_option) {
  if (!normalizeNamespace(ns_option).empty()) {
    servoloop::ipc::IpcClient client = connectToRobotNode(ns_option);
    return nodeTopics(client, normalizeNamespace(ns_option));
  }
  const std::vector<std::string> nodes = runningNodeNames();
  if (nodes.empty()) connectToRobotNode("");  // throws the "no servoloop node is running" error
  nlohmann::json topics = nlohmann::json::array();
  std::optional<std::string> first_error;
  bool answered = false;
  for (const std::string& node_name : nodes) {
    try {
      servoloop::ipc::IpcClient client = connectToNodeNamed(node_name);
      for (auto& topic : nodeTopics(client, node_name)) topics.push_back(std::move(topic));
      answered = true;
    } catch (const Error& error) {
      if (!first_error) first_error = node_name + ": " + error.what();
    }
  }
  if (!answered) throw Error(first_error.value_or("no servoloop node answered"));
  return topics;
}

void runList(const TopicOptions& options) {
  const nlohmann::json topics = listTopics(options.ns);
  if (options.json) {
    std::cout << topics.dump(2) << "\n";
    return;
  }
  // The node column only when the topics come from more than one node.
  std::size_t name_width = 0;
  std::size_t type_width = 0;
  bool several_nodes = false;
  for (const auto& topic : topics) {
    name_width = std::max(name_width, topic.value("name", "").size());
    type_width = std::max(type_width, topic.value("type", "").size());
    several_nodes |= topic.value("node", "") != topics.front().value("node", "");
  }
  for (const auto& topic : topics) {
    const std::string name = topic.value("name", "");
    const std::string type = topic.value("type", "");
    std::cout << name << std::string(name_width - name.size() + 2, ' ') << type;
    if (several_nodes) {
      std::cout << std::string(type_width - type.size() + 2, ' ') << "node " << topic.value("node", "");
    }
    std::cout << "\n";
  }
}

// Rate statistics over the last `window` intervals, as rostopic hz prints them.
class IntervalWindow {
 public:
  explicit IntervalWindow(std::size_t window) : window_(std::max<std::size_t>(window, 1)) {}
  void add(double time_s) {
    if (last_ && time_s > *last_) {
      intervals_.push_back(time_s - *last_);
      if (intervals_.size() > window_) intervals_.pop_front();
    }
    last_ = time_s;
  }
  bool empty() const { return intervals_.empty(); }

  nlohmann::ordered_json stats() const {
    double sum = 0.0;
    double min = intervals_.front();
    double max = intervals_.front();
    for (double interval : intervals_) {
      sum += interval;
      min = std::min(min, interval);
      max = std::max(max, interval);
    }
    const double mean = sum / static_cast<double>(intervals_.size());
    double variance = 0.0;
    for (double interval : intervals_) variance += (interval - mean) * (interval - mean);
    variance /= static_cast<double>(intervals_.size());
    nlohmann::ordered_json out;
    out["rate"] = 1.0 / mean;
    out["min"] = min;
    out["max"] = max;
    out["std_dev"] = std::sqrt(variance);
    out["window"] = intervals_.size();
    return out;
  }

 private:
  std::size_t window_;
  std::optional<double> last_;
  std::deque<double> intervals_;
};

void printRate(const char* clock_name, const IntervalWindow& window) {
  if (window.empty()) {
    std::cout << "average rate (" << clock_name << "): no interval yet\n";
    return;
  }
  const auto stats = window.stats();
  std::cout << std::fixed << "average rate (" << clock_name << "): " << std::setprecision(3)
            << stats["rate"].get<double>() << "\n\tmin: " << stats["min"].get<double>()
            << "s max: " << stats["max"].get<double>()
            << "s std dev: " << std::setprecision(5) << stats["std_dev"].get<double>()
            << "s window: " << stats["window"].get<std::size_t>() << "\n";
  std::cout.unsetf(std::ios::floatfield);
}

void runHz(const TopicOptions& options) {
  if (options.count < 0) throw Error("-n/--count must be >= 0");
  if (options.window == 0) throw Error("--window must be at least 1");
  const std::string topic = resolveName(options.ns, options.topic);
  servoloop::ipc::IpcClient client = connectForName(topic, options.ns);
  IntervalWindow sim(options.window);
  IntervalWindow wall(options.window);
  const auto start = Clock::now();
  auto next_report = start + std::chrono::seconds(1);
  int received = 0;
  bool reported_last = false;

  auto report = [&] {
    if (options.json) {
      nlohmann::ordered_json line;
      line["topic"] = topic;
      line["messages"] = received;
      line["sim"] = sim.empty() ? nlohmann::ordered_json(nullptr) : sim.stats();
      line["wall"] = wall.empty() ? nlohmann::ordered_json(nullptr) : wall.stats();
      std::cout << line.dump() << std::endl;
    } else {
      printRate("sim time", sim);
      printRate("wall time", wall);
      std::cout << std::flush;
    }
  };

  forEachMessage(client, topic, [&](const StreamMessage& message) {
    wall.add(std::chrono::duration<double>(Clock::now() - start).count());
    if (message.stamp) sim.add(*message.stamp);
    ++received;
    reported_last = false;
    if (Clock::now() >= next_report) {
      report();
      reported_last = true;
      next_report += std::chrono::seconds(1);
    }
    return options.count == 0 || received < options.count;
  });
  if (!reported_last) report();
}

void addTopicCommands(CLI::App& root) {
  CLI::App& topic = commandGroup(root, "topic", "Publish, echo and inspect a running node's topics");

  {
    auto options = std::make_shared<TopicOptions>();
    CLI::App* pub = topic.add_subcommand(
        "pub", "Publish a message once, or at a rate with -r until interrupted");
    addNamespaceOption(*pub, options->ns);
    pub->add_option("topic", options->topic, "Topic name")->required();
    pub->add_option("type", options->type, "Message type, e.g. std_msgs/Float64")->required();
    pub->add_option("value", options->value,
                    "A number for std_msgs/Float64, [a, b, ...] for std_msgs/Float64MultiArray, "
                    "YAML or JSON for other types")
        ->required();
    pub->add_option("-r,--rate", options->rate_hz, "Publish at this rate (Hz) until interrupted")
        ->type_name("HZ")
        ->check(numberWithin(1e-6, 1e6, "messages per second"));
    pub->add_option("-n,--count", options->count, "Publish this many messages, then exit")
        ->type_name("COUNT");
    pub->callback([options] { runPub(*options); });
  }
  {
    auto options = std::make_shared<TopicOptions>();
    CLI::App* echo = topic.add_subcommand("echo", "Print the messages published on a topic");
    addNamespaceOption(*echo, options->ns);
    echo->add_option("topic", options->topic, "Topic name")->required();
    echo->add_option("-n,--count", options->count, "Stop after this many messages")
        ->type_name("COUNT");
    echo->add_flag("--json", options->json, "One JSON object per message per line");
    echo->callback([options] { runEcho(*options); });
  }
  {
    auto options = std::make_shared<TopicOptions>();
    CLI::App* list = topic.add_subcommand(
        "list",
        "List the topics of every running node with their types (with --namespace: that node's)");
    list->add_option("-N,--namespace", options->ns,
                     "Robot namespace of the node to list, e.g. /one_DOF_robot (default: every "
                     "running node)")
        ->type_name("NS");
    list->add_flag("--json", options->json,
                   "Print a JSON array of {name, type, publishers, subscribers, node}");
    list->callback([options] { runList(*options); });
  }
  {
    auto options = std::make_shared<TopicOptions>();
    CLI::App* hz = topic.add_subcommand(
        "hz", "Report a topic's publishing rate, in simulated time (stamps) and wall time");
    addNamespaceOption(*hz, options->ns);
    hz->add_option("topic", options->topic, "Topic name")->required();
    hz->add_option("--window", options->window, "Intervals the statistics cover")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}))
        ->type_name("N");
    hz->add_option("-n,--count", options->count, "Stop after this many messages and report")
        ->type_name("COUNT");
    hz->add_flag("--json", options->json,
                 "One JSON object per report: {topic, messages, sim, wall} with rate, min, max, "
                 "std_dev, window");
    hz->callback([options] { runHz(*options); });
  }
}

}  // namespace
}  // namespace servoloop::cli

SERVOLOOP_CLI_COMMANDS(40, servoloop::cli::addTopicCommands)
