#pragma once
// Capturing live topics of running nodes to CSV files, for `servoloop plot
// --topic`: each topic is subscribed over IPC (topic.subscribe) and every
// message it streams is written as a row, in the same format as `servoloop
// launch --record` (time = the message's stamp in simulated seconds), so the
// recording plots exactly like a recorded CSV.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace servoloop::cli {

struct LiveCaptureRequest {
  // Topic names (a relative one is put under `ns`); each is served by the node
  // whose namespace prefixes it, or the --namespace node.
  std::vector<std::string> topics;
  std::string ns;
  // Stop after this much wall time, s; unset: no time limit.
  std::optional<double> duration_s;
  // Stop once the first topic has carried this many messages; 0: no limit.
  std::size_t count = 0;
  // Where the CSV files go (created if missing): <dir>/<topic with '/' as '_'>.csv.
  std::filesystem::path directory;
};

struct LiveRecording {
  std::string topic;  // absolute name
  std::string type;   // empty if no message arrived
  std::filesystem::path csv;
  std::size_t messages = 0;
};

// Subscribes to every topic, then records until the duration has passed, the
// count is reached, or SIGINT/SIGTERM. Every topic gets a file; one that
// carried no message has none written (messages == 0). Throws servoloop::Error
// when no node serves a topic, the node refuses the subscription (e.g. an
// unknown topic), or the node goes away.
std::vector<LiveRecording> captureTopics(const LiveCaptureRequest& request);

// File name for a topic's recording: "/one_DOF_robot/joint_states" ->
// "one_DOF_robot_joint_states.csv".
std::string csvFileNameForTopic(const std::string& topic);

}  // namespace servoloop::cli
