#pragma once
// Records one topic of a TopicBus to a CSV file (the --record flag and the
// launch file's record: list), in the columns of message_json.hpp's csvHeader:
//   sensor_msgs/JointState  time,<joint>.position,<joint>.velocity,<joint>.effort per joint
//   std_msgs/Float64        time,data
//   others                  time,<flattened fields>
// `time` is the message's stamp, simulated seconds. The header is written from
// the first message. Non-real-time: rows are written on the bus's delivery
// thread (or whichever thread flushes the bus).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>

#include "servoloop/node/message_json.hpp"
#include "servoloop/realtime/topic_bus.hpp"

namespace servoloop::node {

class TopicRecorder {
 public:
  // Creates (truncates) `file`, making missing parent folders, and subscribes.
  // Throws servoloop::Error naming the file when it cannot be written.
  TopicRecorder(realtime::TopicBus& bus, std::string topic, std::filesystem::path file);
  // close().
  ~TopicRecorder();
  TopicRecorder(const TopicRecorder&) = delete;
  TopicRecorder& operator=(const TopicRecorder&) = delete;

  // Unsubscribes and flushes the file. A topic that never carried a message
  // leaves a header-only file when its type is known (e.g. time,data), else an
  // empty one (logged as a warning). Idempotent.
  void close();

  const std::string& topic() const { return topic_; }
  const realtime::TopicBus& bus() const { return bus_; }
  const std::filesystem::path& file() const { return file_; }
  // The topic's type once known ("" before the first message).
  std::string type() const;
  std::uint64_t rowsWritten() const;

 private:
  void write(Time stamp, const nlohmann::json& msg);

  realtime::TopicBus& bus_;
  std::string topic_;
  std::filesystem::path file_;
  mutable std::mutex mutex_;  // guards everything below (delivery thread vs close())
  std::ofstream out_;
  std::string type_;
  std::uint64_t rows_ = 0;
  bool closed_ = false;
  realtime::Subscription subscription_;
};

}  // namespace servoloop::node
