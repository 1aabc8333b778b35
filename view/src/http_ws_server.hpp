#pragma once
// An HTTP server with WebSocket connections on one port, made with
// websocketpp on standalone asio (Debian's libwebsocketpp-dev and
// libasio-dev). This header uses only the standard library, so the rest of
// servoloop (C++20) includes it; its .cpp compiles as C++17, the standard
// websocketpp 0.8 is written for. One thread runs the server and owns every
// connection's state; send() from any thread hands its message to it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace servoloop::view {

struct HttpResponse {
  int status = 404;
  std::string content_type = "text/plain; charset=utf-8";
  std::string body;
};

class HttpWsServer {
 public:
  using ConnectionId = std::uint64_t;
  struct Handlers {
    // A GET of `path` (the URL's path, percent-decoded, without the query).
    std::function<HttpResponse(const std::string& path)> http;
    // WebSocket connections on `websocket_path` (others are refused).
    std::function<void(ConnectionId)> opened;
    std::function<void(ConnectionId)> closed;
    std::function<void(ConnectionId, const std::string& text)> message;
  };

  HttpWsServer(Handlers handlers, std::string websocket_path);
  ~HttpWsServer();  // stop()
  HttpWsServer(const HttpWsServer&) = delete;
  HttpWsServer& operator=(const HttpWsServer&) = delete;

  // Binds host:port (port 0: a free one) and starts the server's thread.
  // Throws servoloop::ConfigError naming the address and the fix when it
  // cannot bind (the port in use, an address not on this machine).
  void start(const std::string& host, unsigned port);
  // Closes every connection and ends the thread. Idempotent.
  void stop();
  unsigned port() const;

  // Any thread. Hands a text message to the server's thread, which sends it
  // unless the page has more than `max_buffered` bytes still unsent (a slow
  // page skips messages instead of piling them up). False when the
  // connection is gone.
  bool send(ConnectionId connection, const std::string& text, std::size_t max_buffered = 4u << 20);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace servoloop::view
