// The host hub's HTTP side (Boost.Beast): one session per connection, reading the headers first
// so that POST /print is judged before its body is read, as on the ESP. Routes go to `Routes`.
#pragma once
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <string>

namespace hub {

namespace beast = boost::beast;
namespace http = beast::http;

struct Answer {
  unsigned status = 200;
  std::string contentType = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
};

class HttpSession;

// One of the board's TCP sockets (lwIP's PCBs), held by a connection until it closes: the host hub
// takes no more connections than the board has sockets (they wait, as SYNs an ESP8266 cannot
// answer are sent again). `open` counts them; a WebSocket takes its HTTP session's over.
class SocketSlot {
 public:
  static inline int open = 0;
  static inline void (*freed)() = nullptr;  // a socket came free: accept the next connection
  SocketSlot() : held_(true) { open++; }
  SocketSlot(SocketSlot&& o) noexcept : held_(o.held_) { o.held_ = false; }
  SocketSlot& operator=(SocketSlot&&) = delete;
  ~SocketSlot() {
    if (!held_) return;
    open--;
    if (freed) freed();
  }

 private:
  bool held_;
};

// What the hub does with a request. A POST /print is answered later: the hub keeps `later`.
class Routes {
 public:
  // Before the body: an answer ends the request there; nothing (false) reads the body on. `body`
  // is the session's note of the body it reads (NetworkDesk::arriving), handed back below.
  virtual bool beforeBody(const http::request_parser<http::string_body>& parser, uint32_t& body, Answer& now) = 0;
  // The whole request; false when the answer comes later through `later`.
  virtual bool handle(const http::request<http::string_body>& req, uint32_t body, Answer& now, std::function<void(Answer)> later) = 0;
  // A WebSocket handshake: an answer refuses it (true), or the upgrade goes ahead.
  virtual bool refuseUpgrade(const http::request<http::string_body>& req, Answer& now) = 0;
  virtual void upgrade(beast::tcp_stream&& stream, http::request<http::string_body> req, SocketSlot slot) = 0;
  // The connection went (or was cut off at its deadline) before its body was whole.
  virtual void lost(const http::request_parser<http::string_body>& parser, uint32_t body) = 0;
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket&& socket, Routes& routes, std::chrono::milliseconds deadline)
      : stream_(std::move(socket)), routes_(routes), deadline_(deadline) {}
  void start() { readHeader(); }

 private:
  void readHeader();
  void readBody();
  void dispatch();
  void send(Answer a, bool keepAlive);

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::unique_ptr<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<http::response<http::string_body>> response_;
  Routes& routes_;
  std::chrono::milliseconds deadline_;  // a request is whole within it (http_rules.h)
  uint32_t body_ = 0;
  SocketSlot slot_;
};

}  // namespace hub
