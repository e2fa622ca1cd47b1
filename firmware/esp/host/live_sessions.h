// The host hub's WebSocket side (Boost.Beast): each /ws connection as a session, and the live
// channel's LiveClients over them, as AsyncWebSocket is on the ESP.
#pragma once
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <deque>
#include <memory>
#include <string>

#include "bridge.h"
#include "live_channel.h"

namespace hub {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

class LiveSessions;

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(beast::tcp_stream&& stream, LiveSessions& owner) : ws_(std::move(stream)), owner_(owner) {}
  void start(http::request<http::string_body> req);
  bool trySend(const char* text, uint16_t len);
  void close(uint16_t code, const char* reason);

 private:
  void read();
  void write();
  void sendClose();
  void gone();

  websocket::stream<beast::tcp_stream> ws_;
  LiveSessions& owner_;
  beast::flat_buffer in_;
  std::deque<std::string> out_;
  bool writing_ = false, closing_ = false, left_ = false;
  uint16_t closeCode_ = 1000;
  std::string closeReason_;
  uint8_t id_ = 0;
};

class LiveSessions : public uv::esp::LiveClients {
 public:
  static constexpr size_t kConnectionQueue = 8;  // frames a connection holds, as AsyncWebSocket's queue

  void attach(uv::esp::Bridge& bridge, uv::esp::LiveChannel& live, uint32_t (*nowMs)()) {
    bridge_ = &bridge;
    live_ = &live;
    nowMs_ = nowMs;
  }
  bool trySend(uint8_t client, const char* text, uint16_t len) override;
  void close(uint8_t client, uint16_t code, const char* reason) override;

 private:
  friend class WsSession;
  uint8_t join(const std::shared_ptr<WsSession>& s);
  void leave(uint8_t id);

  uv::esp::Bridge* bridge_ = nullptr;
  uv::esp::LiveChannel* live_ = nullptr;
  uint32_t (*nowMs_)() = nullptr;
  std::weak_ptr<WsSession> sessions_[uv::esp::LiveChannel::kMaxClients + 1];
};

}  // namespace hub
