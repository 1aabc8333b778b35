// Compiled as C++17: websocketpp 0.8's headers do not compile as C++20.
#include "ws_test_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#define ASIO_STANDALONE
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace servoloop::testing {

using Client = websocketpp::client<websocketpp::config::asio_client>;

struct WsTestClient::Impl {
  Client client;
  std::thread thread;
  websocketpp::connection_hdl hdl;
  mutable std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::string> messages;
  bool open = false;
  bool ended = false;
  std::string why;
};

WsTestClient::WsTestClient() : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.client.clear_access_channels(websocketpp::log::alevel::all);
  impl.client.clear_error_channels(websocketpp::log::elevel::all);
  impl.client.init_asio();
  impl.client.set_max_message_size(256u << 20);
  impl.client.set_open_handler([&impl](websocketpp::connection_hdl) {
    std::lock_guard lock(impl.mutex);
    impl.open = true;
    impl.changed.notify_all();
  });
  auto ended = [&impl](websocketpp::connection_hdl hdl) {
    std::lock_guard lock(impl.mutex);
    std::error_code error;
    auto connection = impl.client.get_con_from_hdl(hdl, error);
    if (!error && connection) impl.why = connection->get_ec().message();
    impl.open = false;
    impl.ended = true;
    impl.changed.notify_all();
  };
  impl.client.set_fail_handler(ended);
  impl.client.set_close_handler(ended);
  impl.client.set_message_handler([&impl](websocketpp::connection_hdl, Client::message_ptr message) {
    std::lock_guard lock(impl.mutex);
    impl.messages.push_back(message->get_payload());
    impl.changed.notify_all();
  });
}

WsTestClient::~WsTestClient() { close(); }

bool WsTestClient::connect(const std::string& url, std::chrono::milliseconds timeout) {
  Impl& impl = *impl_;
  std::error_code error;
  Client::connection_ptr connection = impl.client.get_connection(url, error);
  if (error) {
    impl.why = error.message();
    return false;
  }
  impl.hdl = connection->get_handle();
  impl.client.connect(connection);
  impl.thread = std::thread([&impl] {
    try {
      impl.client.run();
    } catch (const std::exception& e) {
      std::lock_guard lock(impl.mutex);
      impl.why = e.what();
      impl.ended = true;
      impl.changed.notify_all();
    }
  });
  std::unique_lock lock(impl.mutex);
  impl.changed.wait_for(lock, timeout, [&] { return impl.open || impl.ended; });
  return impl.open;
}

bool WsTestClient::send(const std::string& text) {
  // The connection is the client thread's: everything that touches it runs there.
  if (!impl_->thread.joinable()) return false;
  asio::post(impl_->client.get_io_service(), [impl = impl_.get(), text] {
    std::error_code error;
    impl->client.send(impl->hdl, text, websocketpp::frame::opcode::text, error);
  });
  return true;
}

std::optional<std::string> WsTestClient::receive(std::chrono::milliseconds timeout) {
  Impl& impl = *impl_;
  std::unique_lock lock(impl.mutex);
  impl.changed.wait_for(lock, timeout, [&] { return !impl.messages.empty() || impl.ended; });
  if (impl.messages.empty()) return std::nullopt;
  std::string message = std::move(impl.messages.front());
  impl.messages.pop_front();
  return message;
}

std::size_t WsTestClient::pending() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->messages.size();
}

bool WsTestClient::isOpen() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->open;
}

void WsTestClient::close() {
  Impl& impl = *impl_;
  if (!impl.thread.joinable()) return;
  asio::post(impl.client.get_io_service(), [&impl] {
    std::error_code error;
    impl.client.close(impl.hdl, websocketpp::close::status::normal, "test done", error);
  });
  {
    std::unique_lock lock(impl.mutex);
    impl.changed.wait_for(lock, std::chrono::seconds(3), [&] { return impl.ended; });
  }
  asio::post(impl.client.get_io_service(), [&impl] { impl.client.stop(); });
  impl.thread.join();
}

void WsTestClient::abort() {
  Impl& impl = *impl_;
  if (!impl.thread.joinable()) return;
  asio::post(impl.client.get_io_service(), [&impl] {
    std::error_code error;
    Client::connection_ptr connection = impl.client.get_con_from_hdl(impl.hdl, error);
    if (!error && connection) connection->get_raw_socket().close(error);
    impl.client.stop();
  });
  impl.thread.join();
}

const std::string& WsTestClient::why() const { return impl_->why; }

nlohmann::json nextOfType(WsTestClient& page, const std::string& type, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    const auto text = page.receive(std::chrono::milliseconds(200));
    if (!text) continue;
    nlohmann::json message = nlohmann::json::parse(*text, nullptr, false);
    if (message.is_object() && message.value("type", "") == type) return message;
  }
  return nullptr;
}

HttpReply httpGet(const std::string& host, unsigned port, const std::string& raw_path) {
  HttpReply reply;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return reply;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  ::inet_pton(AF_INET, host.c_str(), &address.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return reply;
  }
  const std::string request = "GET " + raw_path + " HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n\r\n";
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string response;
  char buffer[65536];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) response.append(buffer, static_cast<std::size_t>(n));
  ::close(fd);
  const auto status_end = response.find("\r\n");
  if (response.rfind("HTTP/1.", 0) != 0 || status_end == std::string::npos) return reply;
  reply.status = std::atoi(response.c_str() + 9);
  const auto headers_end = response.find("\r\n\r\n");
  const std::string headers = response.substr(0, headers_end);
  if (const auto type = headers.find("Content-Type: "); type != std::string::npos) {
    reply.content_type = headers.substr(type + 14, headers.find("\r\n", type) - type - 14);
  }
  if (headers_end != std::string::npos) reply.body = response.substr(headers_end + 4);
  return reply;
}

}  // namespace servoloop::testing
