#include "plot_live.hpp"

#include <chrono>
#include <fstream>
#include <memory>

#include "node_connection.hpp"
#include "servoloop/ipc/ipc_client.hpp"
#include "servoloop/node/message_json.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::cli {
namespace {

using Clock = std::chrono::steady_clock;

// How long one pass over the subscriptions waits for a message, in total.
constexpr double kPollSlice_s = 0.02;

struct Capture {
  LiveRecording recording;
  servoloop::ipc::IpcClient client;
  std::ofstream out;
};

void writeMessage(Capture& capture, const StreamMessage& message) {
  LiveRecording& recording = capture.recording;
  if (recording.messages == 0) {
    recording.type = message.type;
    capture.out.open(recording.csv, std::ios::out | std::ios::trunc);
    if (!capture.out) {
      throw Error("cannot write '" + recording.csv.string() + "' (recording topic '" + recording.topic +
                  "'); choose a writable folder");
    }
    capture.out << servoloop::node::csvHeader(message.type, message.msg) << '\n';
  }
  capture.out << servoloop::node::csvRow(message.type, Time(message.stamp.value_or(0.0)), message.msg) << '\n';
  ++recording.messages;
}

bool timeIsUp(const LiveCaptureRequest& request, Clock::time_point start) {
  return request.duration_s &&
         std::chrono::duration<double>(Clock::now() - start).count() >= *request.duration_s;
}

}  // namespace

std::string csvFileNameForTopic(const std::string& topic) {
  std::string name;
  for (char c : topic) {
    if (c == '/') {
      if (!name.empty()) name += '_';
    } else {
      name += c;
    }
  }
  return (name.empty() ? std::string("topic") : name) + ".csv";
}

std::vector<LiveRecording> captureTopics(const LiveCaptureRequest& request) {
  if (request.topics.empty()) throw Error("nothing to capture: give a topic with --topic");
  if (request.duration_s && !(*request.duration_s > 0.0)) {
    throw Error("--duration must be > 0 (wall seconds to record)");
  }
  std::error_code error;
  std::filesystem::create_directories(request.directory, error);

  std::vector<std::unique_ptr<Capture>> captures;
  for (const std::string& name : request.topics) {
    auto capture = std::make_unique<Capture>();
    capture->recording.topic = resolveName(request.ns, name);
    capture->recording.csv = request.directory / csvFileNameForTopic(capture->recording.topic);
    for (const auto& other : captures) {
      if (other->recording.topic == capture->recording.topic) {
        throw Error("topic '" + capture->recording.topic + "' is given twice; give each --topic once");
      }
    }
    capture->client = connectForName(capture->recording.topic, request.ns);
    captures.push_back(std::move(capture));
  }

  installStopSignalHandlers();
  for (auto& capture : captures) capture->client.call("topic.subscribe", {{"topic", capture->recording.topic}});
  const Clock::time_point start = Clock::now();
  const double slice_s = kPollSlice_s / static_cast<double>(captures.size());
  const LiveRecording& first = captures.front()->recording;

  while (!stopRequested() && !timeIsUp(request, start) &&
         (request.count == 0 || first.messages < request.count)) {
    for (auto& capture : captures) {
      const auto stream = capture->client.readStream(slice_s);
      if (!stream) continue;
      const StreamMessage message = parseStreamMessage(*stream);
      if (message.topic != capture->recording.topic) continue;
      // The count is exact for the first topic: no row beyond it.
      if (&capture->recording == &first && request.count != 0 && first.messages >= request.count) continue;
      writeMessage(*capture, message);
    }
  }

  std::vector<LiveRecording> recordings;
  for (auto& capture : captures) {
    try {
      capture->client.call("topic.unsubscribe", {{"topic", capture->recording.topic}}, 1.0);
    } catch (const std::exception&) {
      // The connection closes right after; the node drops the subscription then.
    }
    capture->out.close();
    recordings.push_back(capture->recording);
  }
  return recordings;
}

}  // namespace servoloop::cli
