#include "servoloop/node/topic_recorder.hpp"

#include <cstring>
#include <system_error>

#include "servoloop/node/message_json.hpp"
#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::node {

TopicRecorder::TopicRecorder(realtime::TopicBus& bus, std::string topic, std::filesystem::path file)
    : bus_(bus), topic_(realtime::TopicBus::normalizeTopicName(topic)), file_(std::move(file)) {
  std::error_code error;
  if (file_.has_parent_path()) std::filesystem::create_directories(file_.parent_path(), error);
  out_.open(file_, std::ios::out | std::ios::trunc);
  if (!out_) {
    throw Error("cannot record topic '" + topic_ + "' to '" + file_.string() + "': " + std::strerror(errno) +
                "; choose a writable file");
  }
  subscription_ = servoloop::node::subscribeJson(bus_, topic_, [this](Time stamp, const nlohmann::json& msg) { write(stamp, msg); });
}

TopicRecorder::~TopicRecorder() { close(); }

void TopicRecorder::write(Time stamp, const nlohmann::json& msg) {
  std::lock_guard lock(mutex_);
  if (closed_) return;
  if (type_.empty()) {
    type_ = bus_.typeOf(topic_);
    out_ << csvHeader(type_, msg) << '\n';
  }
  out_ << csvRow(type_, stamp, msg) << '\n';
  ++rows_;
}

void TopicRecorder::close() {
  // Unsubscribing first waits out a delivery in progress.
  subscription_.reset();
  std::lock_guard lock(mutex_);
  if (closed_) return;
  closed_ = true;
  if (rows_ == 0) {
    std::string type;
    try {
      type = bus_.hasTopic(topic_) ? bus_.typeOf(topic_) : "";
    } catch (const Error&) {
    }
    if (type == std_msgs::Float64::kTypeName) {
      out_ << csvHeader(std_msgs::Float64{}) << '\n';
    } else {
      logger().warn("recording of topic '{}' to '{}': no message arrived; the file is empty", topic_,
                    file_.string());
    }
  }
  out_.flush();
  out_.close();
}

std::string TopicRecorder::type() const {
  std::lock_guard lock(mutex_);
  return type_;
}

std::uint64_t TopicRecorder::rowsWritten() const {
  std::lock_guard lock(mutex_);
  return rows_;
}

}  // namespace servoloop::node
