// /ws on the host hub: Beast WebSocket sessions feeding the same bridge and live channel as the ESP.
#include "live_sessions.h"

#include <nlohmann/json.hpp>

#include "nlohmann_view.h"

namespace hub {

void WsSession::start(http::request<http::string_body> req) {
  auto self = shared_from_this();
  ws_.async_accept(req, [self](beast::error_code ec) {
    if (ec) return;
    self->ws_.text(true);
    self->id_ = self->owner_.join(self);
    if (!self->id_) return self->close(1013, "too many clients");
    self->read();
  });
}

void WsSession::read() {
  auto self = shared_from_this();
  ws_.async_read(in_, [self](beast::error_code ec, size_t) {
    if (ec) return self->gone();
    std::string text = beast::buffers_to_string(self->in_.data());
    self->in_.consume(self->in_.size());
    uv::esp::Bridge& bridge = *self->owner_.bridge_;
    if (!self->ws_.got_text() || text.size() > 256) {
      bridge.clientRefused(self->id_, "too_large", "a message is at most 256 bytes, in one frame");
    } else {
      nlohmann::json m = nlohmann::json::parse(text, nullptr, false);
      if (m.is_discarded()) bridge.clientRefused(self->id_, "bad_json", "not JSON");
      else bridge.clientMessage(self->id_, uvtest::View{&m});
    }
    self->read();
  });
}

bool WsSession::trySend(const char* text, uint16_t len) {
  if (closing_) return true;
  if (out_.size() >= LiveSessions::kConnectionQueue) return false;
  out_.emplace_back(text, len);
  if (!writing_) write();
  return true;
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
  if (left_ || !id_) return;
  left_ = true;
  owner_.leave(id_);
}

uint8_t LiveSessions::join(const std::shared_ptr<WsSession>& s) {
  for (uint8_t i = 1; i <= uv::esp::LiveChannel::kMaxClients; i++) {
    if (!sessions_[i].expired()) continue;
    if (!live_->join(i)) return 0;
    sessions_[i] = s;
    bridge_->clientJoined(i, nowMs_());
    return i;
  }
  return 0;
}

void LiveSessions::leave(uint8_t id) {
  sessions_[id].reset();
  live_->leave(id);
  bridge_->clientLeft(id);
}

bool LiveSessions::trySend(uint8_t client, const char* text, uint16_t len) {
  auto s = client <= uv::esp::LiveChannel::kMaxClients ? sessions_[client].lock() : nullptr;
  return s ? s->trySend(text, len) : true;
}

void LiveSessions::close(uint8_t client, uint16_t code, const char* reason) {
  auto s = client <= uv::esp::LiveChannel::kMaxClients ? sessions_[client].lock() : nullptr;
  if (s) s->close(code, reason);
}

}  // namespace hub
