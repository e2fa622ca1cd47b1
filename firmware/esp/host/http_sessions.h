// The host hub's HTTP side (Boost.Beast): one session per connection, reading the headers first
// so that POST /print is judged before its body is read, as on the ESP. Routes go to `Routes`.
#pragma once
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

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

// What the hub does with a request. A POST /print is answered later: the hub keeps `later`.
class Routes {
 public:
  // Before the body: an answer ends the request there; nothing (false) reads the body on.
  virtual bool beforeBody(const http::request_parser<http::string_body>& parser, Answer& now) = 0;
  // The whole request; false when the answer comes later through `later`.
  virtual bool handle(const http::request<http::string_body>& req, Answer& now, std::function<void(Answer)> later) = 0;
  virtual void upgrade(beast::tcp_stream&& stream, http::request<http::string_body> req) = 0;
  // The connection went before its body was whole, or before its later answer.
  virtual void lost(const http::request_parser<http::string_body>& parser) = 0;
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket&& socket, Routes& routes) : stream_(std::move(socket)), routes_(routes) {}
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
};

}  // namespace hub
