#pragma once
// A node-like IPC server for the tests, with a handler offering a few ops:
//   echo {value}          -> {"value": value}
//   throw {message}       -> throws servoloop::Error(message)
//   throw_non_standard    -> throws an int
//   slow {ms}             -> sleeps, then {"slept_ms": ms}
//   big {bytes}           -> {"payload": "<bytes x 'p'>"}
//   subscribe             -> keeps the connection for push(); onClose forgets it
//   defer                 -> replies 30 ms later from another thread
//   fail_quietly          -> returns {"ok": false} without an error text
//   list                  -> returns an array
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "ipc_test_support.hpp"
#include "servoloop/ipc/ipc_protocol.hpp"
#include "servoloop/ipc/ipc_server.hpp"
#include "servoloop/ipc/ipc_socket_path.hpp"
#include "servoloop/core/errors.hpp"

namespace servoloop::ipc::testing {

inline constexpr const char* kTestNode = "/one_DOF_robot";

class IpcServerFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<IpcServer>(
        socketPathFor(kTestNode),
        [this](const nlohmann::json& request, IpcConnection& connection) {
          return handle(request, connection);
        });
    server_->start();
  }

  void TearDown() override {
    server_->stop();
    for (auto& thread : deferred_threads_) thread.join();
  }

  nlohmann::json handle(const nlohmann::json& request, IpcConnection& connection) {
    ++handler_calls_;
    const std::string op = request["op"];
    if (op == "echo") return {{"value", request.value("value", nlohmann::json())}};
    if (op == "throw") throw Error(request.value("message", std::string("failed")));
    if (op == "throw_non_standard") throw 42;
    if (op == "slow") {
      const int ms = request.value("ms", 100);
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      return {{"slept_ms", ms}};
    }
    if (op == "big") return {{"payload", std::string(request.value("bytes", 1024), 'p')}};
    if (op == "subscribe") {
      std::lock_guard<std::mutex> lock(subscribers_mutex_);
      subscribers_.push_back(connection.shared());
      const std::uint64_t id = connection.id();
      connection.onClose([this, id] {
        std::lock_guard<std::mutex> lock(subscribers_mutex_);
        std::erase_if(subscribers_, [id](const auto& c) { return c->id() == id; });
        ++unsubscribed_;
      });
      return {{"subscribed", true}};
    }
    if (op == "defer") {
      auto shared = connection.shared();
      const nlohmann::json id = request["id"];
      deferred_threads_.emplace_back([shared, id] {
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
        shared->sendDeferredReply(makeIpcOkReply(id, {{"deferred", true}}));
      });
      return IpcServer::deferredReply();
    }
    if (op == "fail_quietly") return {{"ok", false}};
    if (op == "list") return nlohmann::json::array({1, 2, 3});
    throw Error("unknown op '" + op + "'");
  }

  // Subscribed connections, copied out so the caller pushes without the lock.
  std::vector<std::shared_ptr<IpcConnection>> subscribers() {
    std::lock_guard<std::mutex> lock(subscribers_mutex_);
    return subscribers_;
  }

  ScopedRunDir run_dir_;
  std::unique_ptr<IpcServer> server_;
  std::atomic<int> handler_calls_{0};
  std::atomic<int> unsubscribed_{0};
  std::mutex subscribers_mutex_;
  std::vector<std::shared_ptr<IpcConnection>> subscribers_;
  std::vector<std::thread> deferred_threads_;  // service thread only, joined in TearDown
};

}  // namespace servoloop::ipc::testing
