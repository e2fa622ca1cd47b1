// One ring of live messages, read by each WebSocket client at its own pace.
#include "live_channel.h"

#include <string.h>

namespace uv {
namespace esp {

bool LiveChannel::join(uint8_t client) {
  for (Reader& r : readers_) {
    if (!r.used) {
      r = {true, client, head_};
      return true;
    }
  }
  return false;
}

void LiveChannel::leave(uint8_t client) {
  for (Reader& r : readers_)
    if (r.used && r.id == client) r.used = false;
}

uint8_t LiveChannel::count() const {
  uint8_t n = 0;
  for (const Reader& r : readers_) n = static_cast<uint8_t>(n + r.used);
  return n;
}

uint32_t LiveChannel::lag(uint8_t client) const {
  for (const Reader& r : readers_)
    if (r.used && r.id == client) return head_ - r.at;
  return 0;
}

// Readers that would be overwritten by writing up to `upTo` are too slow: closed and dropped.
void LiveChannel::makeRoom(uint32_t upTo) {
  for (Reader& r : readers_) {
    if (r.used && upTo - r.at > kRing) {
      r.used = false;
      closedSlow_++;
      clients_.close(r.id, 1008, "too slow");
    }
  }
}

bool LiveChannel::put(uint8_t to, const char* text, uint16_t len) {
  if (len > kMaxMessage) return false;
  uint16_t at = static_cast<uint16_t>(head_ % kRing);
  uint32_t need = kHeader + len;
  if (at + need > kRing) {  // no room before the end: mark a wrap, go on at the ring's start
    uint32_t skip = kRing - at;
    makeRoom(head_ + skip + need);
    if (skip >= kHeader) {
      ring_[at] = static_cast<char>(kWrap & 0xff);
      ring_[at + 1] = static_cast<char>(kWrap >> 8);
    }
    head_ += skip;
    at = 0;
  }
  makeRoom(head_ + need);
  ring_[at] = static_cast<char>(len & 0xff);
  ring_[at + 1] = static_cast<char>(len >> 8);
  ring_[at + 2] = static_cast<char>(to);
  ring_[at + 3] = 0;
  memcpy(ring_ + at + kHeader, text, len);
  head_ += need;
  return true;
}

bool LiveChannel::entry(uint32_t& at, uint16_t& len, uint8_t& to, const char*& text) const {
  for (;;) {
    if (at == head_) return false;
    uint16_t i = static_cast<uint16_t>(at % kRing);
    if (kRing - i < kHeader) {  // a tail too short for a header: the writer skipped it
      at += kRing - i;
      continue;
    }
    len = static_cast<uint16_t>(static_cast<uint8_t>(ring_[i]) | static_cast<uint8_t>(ring_[i + 1]) << 8);
    if (len == kWrap) {
      at += kRing - i;
      continue;
    }
    to = static_cast<uint8_t>(ring_[i + 2]);
    text = ring_ + i + kHeader;
    return true;
  }
}

void LiveChannel::pump() {
  for (Reader& r : readers_) {
    uint16_t len;
    uint8_t to;
    const char* text;
    while (r.used && entry(r.at, len, to, text)) {
      if ((to == kEveryone || to == r.id) && !clients_.trySend(r.id, text, len)) break;
      r.at += kHeader + len;
    }
  }
}

}  // namespace esp
}  // namespace uv
