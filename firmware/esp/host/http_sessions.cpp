// HTTP/1.1 sessions on the host hub: headers first, then the body, then the route's answer.
#include "http_sessions.h"

#include <boost/beast/websocket.hpp>

#include "http_rules.h"

namespace hub {

void HttpSession::readHeader() {
  parser_ = std::make_unique<http::request_parser<http::string_body>>();
  parser_->body_limit(2 * 1024 * 1024);  // the routes judge Content-Length themselves
  parser_->header_limit(uv::esp::kHeaderBytesMax);
  body_ = 0;
  // The request's deadline, from when it may start (a connection that keeps alive and says
  // nothing is let go at it too): a client that sends a byte every 2.9 s holds nothing for long.
  stream_.expires_after(deadline_);
  auto self = shared_from_this();
  http::async_read_header(stream_, buffer_, *parser_, [self](beast::error_code ec, size_t) {
    if (ec) return;  // its deadline, its header limit, or its client gone: the connection closes
    Answer now;
    if (self->routes_.beforeBody(*self->parser_, self->body_, now)) {
      // Judged on its headers: answer and close, without reading a body that may be 1 MB.
      return self->send(std::move(now), false);
    }
    self->readBody();
  });
}

void HttpSession::readBody() {
  auto self = shared_from_this();
  http::async_read(stream_, buffer_, *parser_, [self](beast::error_code ec, size_t) {
    if (ec) return self->routes_.lost(*self->parser_, self->body_);
    self->dispatch();
  });
}

void HttpSession::dispatch() {
  http::request<http::string_body> req = parser_->release();
  stream_.expires_never();  // whole in time; an answer that waits for loop() is not the client's fault
  Answer now;
  if (boost::beast::websocket::is_upgrade(req)) {
    if (routes_.refuseUpgrade(req, now)) return send(std::move(now), false);
    return routes_.upgrade(std::move(stream_), std::move(req), std::move(slot_));
  }
  bool keepAlive = false;  // as ESPAsyncWebServer: every answer says Connection: close, and closes
  auto self = shared_from_this();
  if (routes_.handle(req, body_, now, [self, keepAlive](Answer a) { self->send(std::move(a), keepAlive); })) send(std::move(now), keepAlive);
}

void HttpSession::send(Answer a, bool keepAlive) {
  response_ = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(a.status), 11);
  response_->set(http::field::server, "UVExposure ESP (host)");
  if (!a.contentType.empty()) response_->set(http::field::content_type, a.contentType);
  for (auto& h : a.headers) response_->set(h.first, h.second);
  response_->body() = std::move(a.body);
  response_->keep_alive(keepAlive);
  response_->prepare_payload();
  auto self = shared_from_this();
  http::async_write(stream_, *response_, [self, keepAlive](beast::error_code ec, size_t) {
    if (ec || !keepAlive) {
      beast::error_code ignored;
      self->stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ignored);
      return;
    }
    self->readHeader();
  });
}

}  // namespace hub
