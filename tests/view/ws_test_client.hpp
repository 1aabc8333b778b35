#pragma once
// A WebSocket client for tests (websocketpp on standalone asio, as the view
// server): connect to ws://HOST:PORT/PATH, send and receive text messages,
// close politely or drop the connection mid-transfer. Also a plain HTTP GET.
// Only the standard library and nlohmann-json here: the .cpp compiles as C++17.
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace servoloop::testing {

class WsTestClient {
 public:
  WsTestClient();
  ~WsTestClient();  // close()
  WsTestClient(const WsTestClient&) = delete;
  WsTestClient& operator=(const WsTestClient&) = delete;

  // Connects and waits for the handshake; false (with why()) on failure.
  bool connect(const std::string& url, std::chrono::milliseconds timeout = std::chrono::seconds(10));
  bool send(const std::string& text);
  // The next message, or nullopt when none comes in time (or it closed).
  std::optional<std::string> receive(std::chrono::milliseconds timeout);
  // Messages received so far and not taken.
  std::size_t pending() const;
  bool isOpen() const;
  // The closing handshake, then the thread ends.
  void close();
  // The TCP connection closed at once, with no closing handshake (a page
  // killed mid-transfer).
  void abort();
  const std::string& why() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The next message of the view's protocol whose "type" is `type`, skipping
// others; null when none comes in `timeout`.
nlohmann::json nextOfType(WsTestClient& page, const std::string& type,
                          std::chrono::milliseconds timeout = std::chrono::seconds(20));

// A GET of http://HOST:PORT/PATH as sent (no normalisation of "..", as a
// hostile client would send it): the status code and body; status 0 when
// nothing answered.
struct HttpReply {
  int status = 0;
  std::string content_type;
  std::string body;
};
HttpReply httpGet(const std::string& host, unsigned port, const std::string& raw_path);

}  // namespace servoloop::testing
