// /ws on the host hub: Beast WebSocket sessions feeding the same inbox, bridge and live channel as
// the ESP's glue.
#include "live_sessions.h"

#include <nlohmann/json.hpp>

#include "nlohmann_view.h"

namespace hub {

void WsSession::start(http::request<http::string_body> req) {
  auto self = shared_from_this();
  ws_.read_message_max(64 * 1024);  // a longer one is read and refused (too_large), as the ESP does
  ws_.async_accept(req, [self](beast::error_code ec) {
    if (ec) return;
    self->ws_.text(true);
    self->name_ = self->owner_.join(self);
    if (!self->name_) return self->close(1013, "too many clients");
    self->read();
  });
}

void WsSession::read() {
  auto self = shared_from_this();
  ws_.async_read(in_, [self](beast::error_code ec, size_t) {
    if (ec) return self->gone();
    std::string text = beast::buffers_to_string(self->in_.data());
    self->in_.consume(self->in_.size());
    if (self->ws_.got_text()) {
      uv::esp::LiveInbox& inbox = self->owner_.inbox_;
      if (inbox.received(self->name_, text.data(), text.size(), true, true) == uv::esp::LiveInbox::Piece::Busy) {
        nlohmann::json m = nlohmann::json::parse(std::string(inbox.busyText(), inbox.busyLength()), nullptr, false);
        bool hasId = m.is_object() && m.contains("id") && m["id"].is_number_integer();
        char busy[160];
        uv::esp::JsonWriter w(busy, sizeof busy);
        uv::esp::writeBusy(w, hasId, hasId ? m["id"].get<int64_t>() : 0);
        self->queue(w.text(), w.length());  // the network side answers it itself
      }
    }
    self->read();
  });
}

// The library's queue: a frame past WS_MAX_QUEUED_MESSAGES would be dropped (ESPAsyncWebServer
// discards it, or closes the client); the live channel never gets that far.
bool WsSession::queue(const char* text, size_t len) {
  if (closing_ || out_.size() >= owner_.board_.wsQueue) return false;
  out_.emplace_back(text, len);
  owner_.deepest_ = std::max(owner_.deepest_, out_.size());
  if (!writing_) write();
  return true;
}

// As the glue's: only when the client's queue is empty.
bool WsSession::trySend(const char* text, uint16_t len) {
  if (closing_) return true;
  if (!out_.empty()) return false;
  return queue(text, len);
}

void WsSession::write() {
  if (closing_) {
    writing_ = false;
    return sendClose();
  }
  if (out_.empty()) {
    writing_ = false;
    return;
  }
  writing_ = true;
  auto self = shared_from_this();
  ws_.async_write(boost::asio::buffer(out_.front()), [self](beast::error_code ec, size_t) {
    if (ec) return self->gone();
    self->out_.pop_front();
    self->write();
  });
}

// A close is a write too: it waits for the frame being written.
void WsSession::close(uint16_t code, const char* reason) {
  if (closing_) return;
  closing_ = true;
  closeCode_ = code;
  closeReason_ = reason;
  if (writing_) out_.erase(out_.begin() + 1, out_.end());  // the frame on the wire stays till it is written
  else out_.clear();
  if (!writing_) sendClose();
}

void WsSession::sendClose() {
  auto self = shared_from_this();
  ws_.async_close(websocket::close_reason(static_cast<websocket::close_code>(closeCode_), closeReason_), [self](beast::error_code) { self->gone(); });
}

void WsSession::gone() {
  if (left_ || !name_) return;
  left_ = true;
  owner_.leave(name_);
}

uint8_t LiveSessions::join(const std::shared_ptr<WsSession>& s) {
  uint8_t name = inbox_.join(board_.wsClients);
  if (!name) return 0;
  if (!live_->join(name)) {
    inbox_.leave(name);
    return 0;
  }
  sessions_[name] = s;
  return name;
}

void LiveSessions::leave(uint8_t name) {
  sessions_[name].reset();
  live_->leave(name);
  inbox_.leave(name);
}

void LiveSessions::drain() {
  inbox_.drain(
      [this](const uv::esp::LiveInbox::Member& m) {
        if (m.kind == uv::esp::LiveInbox::Kind::Joined) bridge_->clientJoined(m.client, nowMs_());
        else bridge_->clientLeft(m.client);
      },
      [this](const uv::esp::LiveInbox::Message& m) {
        if (m.kind == uv::esp::LiveInbox::Kind::TooLarge) return bridge_->clientRefused(m.client, "too_large", "a message is at most 256 bytes");
        nlohmann::json j = nlohmann::json::parse(std::string(m.text, m.len), nullptr, false);
        if (j.is_discarded()) return bridge_->clientRefused(m.client, "bad_json", "not JSON");
        bridge_->clientMessage(m.client, uvtest::View{&j});
      });
}

bool LiveSessions::trySend(uint8_t client, const char* text, uint16_t len) {
  auto s = sessions_[client].lock();
  return s ? s->trySend(text, len) : true;
}

void LiveSessions::close(uint8_t client, uint16_t code, const char* reason) {
  auto s = sessions_[client].lock();
  if (s) s->close(code, reason);
}

}  // namespace hub
