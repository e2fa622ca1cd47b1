// One ring of live messages, read by each WebSocket client at its own pace (live_channel.h).
#include "live_channel.h"

namespace uv {
namespace esp {

bool LiveChannel::join(uint8_t client) {
  for (Reader& r : readers_) {
    if (r.used.load(std::memory_order_relaxed)) continue;
    r.id = client;
    r.at = head_.load(std::memory_order_acquire);
    r.greeted = false;
    r.used.store(true, std::memory_order_release);
    return true;
  }
  return false;
}

void LiveChannel::leave(uint8_t client) {
  for (Reader& r : readers_)
    if (r.used.load(std::memory_order_relaxed) && r.id == client) r.used.store(false, std::memory_order_release);
}

uint8_t LiveChannel::count() const {
  uint8_t n = 0;
  for (const Reader& r : readers_) n = static_cast<uint8_t>(n + r.used.load(std::memory_order_acquire));
  return n;
}

uint32_t LiveChannel::lag(uint8_t client) const {
  for (const Reader& r : readers_)
    if (r.used.load(std::memory_order_relaxed) && r.id == client) return head_.load(std::memory_order_acquire) - r.at;
  return 0;
}

// The writer never waits and never looks at the readers: it announces the bytes it is about to
// write (reserved_), writes them, then publishes them (head_).
bool LiveChannel::put(uint8_t to, const char* text, uint16_t len) {
  if (len > kMaxMessage) return false;
  uint32_t head = head_.load(std::memory_order_relaxed);  // the writer's own
  uint16_t at = static_cast<uint16_t>(head % kRing);
  uint32_t need = kHeader + len;
  uint32_t skip = at + need > kRing ? kRing - at : 0;  // no room before the end: wrap to the start
  reserved_.store(head + skip + need, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);  // a reader that sees a byte below sees the reservation
  if (skip) {
    if (skip >= kHeader) {
      store(at, static_cast<char>(kWrap & 0xff));
      store(static_cast<uint16_t>(at + 1), static_cast<char>(kWrap >> 8));
    }
    head += skip;
    at = 0;
  }
  store(at, static_cast<char>(len & 0xff));
  store(static_cast<uint16_t>(at + 1), static_cast<char>(len >> 8));
  store(static_cast<uint16_t>(at + 2), static_cast<char>(to));
  store(static_cast<uint16_t>(at + 3), 0);
  for (uint16_t i = 0; i < len; i++) store(static_cast<uint16_t>(at + kHeader + i), text[i]);
  head_.store(head + need, std::memory_order_release);
  return true;
}

bool LiveChannel::entry(uint32_t& at, uint32_t head, uint16_t& len, uint8_t& to) const {
  for (;;) {
    if (at == head) return false;
    uint16_t i = static_cast<uint16_t>(at % kRing);
    if (kRing - i < kHeader) {  // a tail too short for a header: the writer skipped it
      at += kRing - i;
      continue;
    }
    len = static_cast<uint16_t>(byteAt(i) | byteAt(i + 1u) << 8);
    if (len == kWrap) {
      at += kRing - i;
      continue;
    }
    to = byteAt(i + 2u);
    return true;
  }
}

void LiveChannel::evict(Reader& r) {
  r.used.store(false, std::memory_order_release);
  closedSlow_.fetch_add(1, std::memory_order_relaxed);
  clients_.close(r.id, 1008, "too slow");
}

void LiveChannel::pump() {
  uint32_t head = head_.load(std::memory_order_acquire);
  bool blocked = false;
  for (Reader& r : readers_) {
    while (r.used.load(std::memory_order_relaxed)) {
      if (head - r.at > kRing) {  // the writer has passed it: what it has not read is gone
        evict(r);
        break;
      }
      uint32_t at = r.at;
      uint16_t len = 0;
      uint8_t to = 0;
      if (!entry(at, head, len, to)) {
        r.at = at;
        break;
      }
      // Until its greeting, a broadcast is not yet for it: loop() had not heard of the client.
      bool mine = to == r.id || (to == kEveryone && r.greeted);
      uint16_t i = static_cast<uint16_t>(at % kRing);
      bool fits = len <= kMaxMessage && i + kHeader + len <= kRing;
      if (mine && fits)
        for (uint16_t k = 0; k < len; k++) copy_[k] = static_cast<char>(byteAt(i + kHeader + k));
      // The seqlock's check: had the writer reserved these bytes again before they were copied?
      std::atomic_thread_fence(std::memory_order_acquire);
      if (reserved_.load(std::memory_order_relaxed) - at > kRing || !fits) {  // torn, so a ring behind
        evict(r);
        break;
      }
      if (mine && !clients_.trySend(r.id, copy_, len)) {
        r.at = at;  // its connection is full: the message waits in the ring
        blocked = true;
        break;
      }
      r.at = at + kHeader + len;
      if (to == r.id) r.greeted = true;
    }
  }
  backlog_.store(blocked, std::memory_order_relaxed);
}

}  // namespace esp
}  // namespace uv
