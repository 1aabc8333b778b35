// Compiled as C++17 (view/CMakeLists.txt): websocketpp 0.8's headers do not
// compile as C++20.
#include "http_ws_server.hpp"

#include <map>
#include <mutex>
#include <thread>

#define ASIO_STANDALONE
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "servoloop/core/errors.hpp"

namespace servoloop::view {

namespace {

using Server = websocketpp::server<websocketpp::config::asio>;

// "%2e%2E" and "+" as a browser sends them; an invalid escape stays as it is.
std::string percentDecoded(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out.push_back(static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(text[i]);
    }
  }
  return out;
}

}  // namespace

struct HttpWsServer::Impl {
  Handlers handlers;
  std::string websocket_path;
  Server server;
  std::thread thread;
  unsigned port = 0;
  bool running = false;

  std::mutex connections_mutex;
  std::map<ConnectionId, websocketpp::connection_hdl> connections;
  std::map<websocketpp::connection_hdl, ConnectionId, std::owner_less<websocketpp::connection_hdl>> ids;
  ConnectionId next_id = 1;
};

HttpWsServer::HttpWsServer(Handlers handlers, std::string websocket_path) : impl_(std::make_unique<Impl>()) {
  impl_->handlers = std::move(handlers);
  impl_->websocket_path = std::move(websocket_path);
  Impl& impl = *impl_;
  Server& server = impl.server;
  server.clear_access_channels(websocketpp::log::alevel::all);
  server.clear_error_channels(websocketpp::log::elevel::all);
  server.init_asio();
  server.set_reuse_addr(true);
  server.set_http_handler([&impl](websocketpp::connection_hdl hdl) {
    Server::connection_ptr connection = impl.server.get_con_from_hdl(hdl);
    std::string path = connection->get_request().get_uri();
    if (const auto query = path.find_first_of("?#"); query != std::string::npos) path.resize(query);
    HttpResponse response;
    if (connection->get_request().get_method() != "GET" && connection->get_request().get_method() != "HEAD") {
      response = {405, "text/plain; charset=utf-8", "only GET is served here\n"};
    } else {
      try {
        response = impl.handlers.http(percentDecoded(path));
      } catch (const std::exception& error) {
        response = {500, "text/plain; charset=utf-8", std::string(error.what()) + "\n"};
      }
    }
    connection->set_status(static_cast<websocketpp::http::status_code::value>(response.status));
    connection->replace_header("Content-Type", response.content_type);
    connection->replace_header("Cache-Control", "no-store");
    connection->set_body(std::move(response.body));
  });
  server.set_validate_handler([&impl](websocketpp::connection_hdl hdl) {
    return impl.server.get_con_from_hdl(hdl)->get_resource() == impl.websocket_path;
  });
  server.set_open_handler([&impl](websocketpp::connection_hdl hdl) {
    ConnectionId id = 0;
    {
      std::lock_guard lock(impl.connections_mutex);
      id = impl.next_id++;
      impl.connections[id] = hdl;
      impl.ids[hdl] = id;
    }
    if (impl.handlers.opened) impl.handlers.opened(id);
  });
  auto forget = [&impl](websocketpp::connection_hdl hdl) {
    ConnectionId id = 0;
    {
      std::lock_guard lock(impl.connections_mutex);
      const auto it = impl.ids.find(hdl);
      if (it == impl.ids.end()) return;
      id = it->second;
      impl.connections.erase(id);
      impl.ids.erase(it);
    }
    if (impl.handlers.closed) impl.handlers.closed(id);
  };
  server.set_close_handler(forget);
  server.set_fail_handler(forget);
  server.set_message_handler([&impl](websocketpp::connection_hdl hdl, Server::message_ptr message) {
    ConnectionId id = 0;
    {
      std::lock_guard lock(impl.connections_mutex);
      const auto it = impl.ids.find(hdl);
      if (it == impl.ids.end()) return;
      id = it->second;
    }
    if (impl.handlers.message && message->get_opcode() == websocketpp::frame::opcode::text) {
      impl.handlers.message(id, message->get_payload());
    }
  });
  // A page is small; a request larger than this is not from it.
  server.set_max_message_size(64 * 1024);
  server.set_max_http_body_size(64 * 1024);
}

HttpWsServer::~HttpWsServer() { stop(); }

void HttpWsServer::start(const std::string& host, unsigned port) {
  Impl& impl = *impl_;
  std::error_code error;
  const asio::ip::address address = asio::ip::make_address(host, error);
  if (error) {
    throw ConfigError("view: '" + host + "' is not an IP address; give one such as 127.0.0.1 (this machine only) or " +
                      "0.0.0.0 (every network), e.g. --view 127.0.0.1:8080");
  }
  impl.server.listen(asio::ip::tcp::endpoint(address, static_cast<unsigned short>(port)), error);
  if (error) {
    if (error == asio::error::address_in_use) {
      throw ConfigError("view: port " + std::to_string(port) + " on " + host +
                        " is in use by another program; choose a free one with --view " + host + ":PORT (or " +
                        host + ":0 for any free port)");
    }
    throw ConfigError("view: cannot listen on " + host + ":" + std::to_string(port) + " (" + error.message() +
                      "); give an address of this machine, e.g. --view 127.0.0.1:8080");
  }
  impl.server.start_accept(error);
  if (error) throw ConfigError("view: cannot accept connections on " + host + ":" + std::to_string(port) + " (" + error.message() + ")");
  asio::error_code local_error;
  impl.port = impl.server.get_local_endpoint(local_error).port();
  impl.running = true;
  impl.thread = std::thread([&impl] {
    try {
      impl.server.run();
    } catch (const std::exception&) {
      // A failure inside asio ends the server; the node runs on.
    }
  });
}

void HttpWsServer::stop() {
  Impl& impl = *impl_;
  if (!impl.running) return;
  impl.running = false;
  // The listening socket and the connections are the server thread's: it
  // closes them itself, then ends its loop.
  asio::post(impl.server.get_io_service(), [&impl] {
    std::error_code error;
    impl.server.stop_listening(error);
    std::map<ConnectionId, websocketpp::connection_hdl> open;
    {
      std::lock_guard lock(impl.connections_mutex);
      open = impl.connections;
    }
    for (auto& [id, hdl] : open) impl.server.close(hdl, websocketpp::close::status::going_away, "the view stops", error);
    impl.server.stop();
  });
  if (impl.thread.joinable()) impl.thread.join();
}

unsigned HttpWsServer::port() const { return impl_->port; }

bool HttpWsServer::send(ConnectionId connection, const std::string& text, std::size_t max_buffered) {
  Impl& impl = *impl_;
  websocketpp::connection_hdl hdl;
  {
    std::lock_guard lock(impl.connections_mutex);
    const auto it = impl.connections.find(connection);
    if (it == impl.connections.end()) return false;
    hdl = it->second;
  }
  // A connection's state is the server thread's: the message is handed to
  // it, which drops it when the page has more than `max_buffered` unsent.
  auto message = std::make_shared<const std::string>(text);
  asio::post(impl.server.get_io_service(), [&impl, hdl, message, max_buffered] {
    std::error_code error;
    Server::connection_ptr con = impl.server.get_con_from_hdl(hdl, error);
    if (error || !con || con->get_state() != websocketpp::session::state::open) return;
    if (con->get_buffered_amount() > max_buffered) return;
    con->send(*message, websocketpp::frame::opcode::text);
  });
  return true;
}

}  // namespace servoloop::view
