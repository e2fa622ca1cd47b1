// The host hub's WebSocket side (Boost.Beast): each /ws connection as a session, as AsyncWebSocket
// is on the ESP: the board's cap on clients, each client's queue of at most the library's
// WS_MAX_QUEUED_MESSAGES frames, and the same rules as the glue (arduino/live_socket.cpp): the
// clients' messages go to loop() through the inbox (live_inbox.h), the live channel's go out only
// to a connection whose queue is empty.
#pragma once
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <deque>
#include <memory>
#include <string>

#include "board.h"
#include "bridge.h"
#include "http_sessions.h"
#include "live_channel.h"
#include "live_inbox.h"

namespace hub {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

class LiveSessions;

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(beast::tcp_stream&& stream, LiveSessions& owner, SocketSlot slot) : ws_(std::move(stream)), owner_(owner), slot_(std::move(slot)) {}
  void start(http::request<http::string_body> req);
  bool trySend(const char* text, uint16_t len);
  void close(uint16_t code, const char* reason);
  size_t queued() const { return out_.size(); }

 private:
  void read();
  void write();
  void sendClose();
  void gone();
  bool queue(const char* text, size_t len);

  websocket::stream<beast::tcp_stream> ws_;
  LiveSessions& owner_;
  SocketSlot slot_;
  beast::flat_buffer in_;
  std::deque<std::string> out_;
  bool writing_ = false, closing_ = false, left_ = false;
  uint16_t closeCode_ = 1000;
  std::string closeReason_;
  uint8_t name_ = 0;
};

class LiveSessions : public uv::esp::LiveClients {
 public:
  explicit LiveSessions(const uv::esp::Board& board) : board_(board) {}
  void attach(uv::esp::Bridge& bridge, uv::esp::LiveChannel& live, uint32_t (*nowMs)()) {
    bridge_ = &bridge;
    live_ = &live;
    nowMs_ = nowMs;
  }
  // loop()'s side: the clients' joins, leaves and messages to the bridge.
  void drain();
  bool trySend(uint8_t client, const char* text, uint16_t len) override;
  void close(uint8_t client, uint16_t code, const char* reason) override;
  const uv::esp::Board& board() const { return board_; }
  // The deepest any client's queue has been: the library's limit is never reached.
  size_t deepestQueue() const { return deepest_; }

 private:
  friend class WsSession;
  uint8_t join(const std::shared_ptr<WsSession>& s);
  void leave(uint8_t name);

  uv::esp::Board board_;
  uv::esp::LiveInbox inbox_;
  uv::esp::Bridge* bridge_ = nullptr;
  uv::esp::LiveChannel* live_ = nullptr;
  uint32_t (*nowMs_)() = nullptr;
  std::weak_ptr<WsSession> sessions_[256];  // by name
  size_t deepest_ = 0;
};

}  // namespace hub
