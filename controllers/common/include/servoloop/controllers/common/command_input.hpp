#pragma once
// A controller's command topic as the real-time thread sees it: the newest
// valid command, taken without blocking or allocating. Commands that cannot
// be used (a NaN or infinite value, a list of the wrong length) are ignored —
// the controller keeps its previous command — and counted; the first one of
// each kind is also logged, off the real-time thread, by a subscriber on the
// bus's delivery thread.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "servoloop/realtime/messages.hpp"
#include "servoloop/realtime/realtime_subscriber.hpp"
#include "servoloop/realtime/topic_subscription.hpp"

namespace servoloop::realtime {
class TopicBus;
}

namespace servoloop::controllers {

// Counts of ignored commands (any thread may read them).
struct RejectedCommands {
  std::atomic<std::uint64_t> non_finite{0};
  std::atomic<std::uint64_t> wrong_size{0};
};

// std_msgs/Float64 commands.
class ScalarCommandInput {
 public:
  ScalarCommandInput() = default;
  ScalarCommandInput(const ScalarCommandInput&) = delete;
  ScalarCommandInput& operator=(const ScalarCommandInput&) = delete;

  // Non-real-time. Subscribes to topic on bus (nothing happens when bus is
  // null: the input then never has a command). controller_name is used in log messages.
  void connect(servoloop::realtime::TopicBus* bus, const std::string& topic,
               const std::string& controller_name);

  // Real-time. Forgets commands published so far (a controller's starting()).
  void clear() noexcept { input_.clear(); }

  // Real-time: whether a command arrived since the last takeNew() (cheap; a
  // controller checks it before calling takeNew()).
  bool hasNew() const noexcept { return input_.hasNewMessage(); }

  // Real-time. If a command arrived since the last call and it is finite,
  // writes it to value and returns true. A non-finite one is counted and
  // false is returned (value untouched).
  bool takeNew(double& value) noexcept;

  const std::string& topic() const noexcept { return topic_; }
  std::uint64_t rejectedNonFinite() const noexcept {
    return rejected_->non_finite.load(std::memory_order_relaxed);
  }

 private:
  servoloop::realtime::RealtimeSubscriber<servoloop::std_msgs::Float64> input_;  // first: hasNew() every cycle
  std::string topic_;
  servoloop::realtime::Subscription checker_;  // logs the first bad command, off the real-time thread
  std::shared_ptr<RejectedCommands> rejected_ = std::make_shared<RejectedCommands>();
};

// std_msgs/Float64MultiArray commands of a fixed length (one per joint).
class ArrayCommandInput {
 public:
  ArrayCommandInput() = default;
  ArrayCommandInput(const ArrayCommandInput&) = delete;
  ArrayCommandInput& operator=(const ArrayCommandInput&) = delete;

  // Non-real-time. size: the number of values a command must have.
  void connect(servoloop::realtime::TopicBus* bus, const std::string& topic, std::size_t size,
               const std::string& controller_name);

  void clear() noexcept { input_.clear(); }

  // Real-time. If a command arrived since the last call, has size() values
  // and all are finite, copies them into values (which must already have
  // size() elements) and returns true; otherwise counts it and returns false.
  bool takeNew(std::vector<double>& values) noexcept;

  std::size_t size() const noexcept { return size_; }
  const std::string& topic() const noexcept { return topic_; }
  std::uint64_t rejectedNonFinite() const noexcept {
    return rejected_->non_finite.load(std::memory_order_relaxed);
  }
  std::uint64_t rejectedWrongSize() const noexcept {
    return rejected_->wrong_size.load(std::memory_order_relaxed);
  }

 private:
  std::string topic_;
  std::size_t size_ = 0;
  servoloop::realtime::RealtimeSubscriber<servoloop::std_msgs::Float64MultiArray> input_;
  servoloop::realtime::Subscription checker_;
  std::shared_ptr<RejectedCommands> rejected_ = std::make_shared<RejectedCommands>();
};

}  // namespace servoloop::controllers
