// The WebSocket clients' side of /ws on its way to loop() (protocol/esp.md "WebSocket"): who joins
// and who leaves, and each client's messages, put in by the network task (which alone touches the
// WebSocket library) and taken by loop() (which alone touches the bridge), through two fixed
// rings without a lock (spsc_ring.h).
// - Joining and leaving never get lost: a client joins only when its Joined and its later Left
//   both have room, so a `send` waiting for its `reply` always learns that its client left.
// - A message may come in pieces (frames, and TCP segments of a frame): up to kMaxFrame bytes it
//   is put together; a longer one is refused whole (`too_large`).
// - A whole message with no room is refused at once (`busy`), never dropped without a word.
// - Clients are named by a byte that is not given again for 250 joins, so what loop() still says
//   to a client that left never reaches one that joined after it.
#pragma once
#include <stdint.h>
#include <string.h>

#include "json_writer.h"
#include "live_channel.h"
#include "spsc_ring.h"

namespace uv {
namespace esp {

class LiveInbox {
 public:
  static constexpr uint16_t kMaxFrame = 256;  // a `send` is under 150 bytes of JSON
  static constexpr uint8_t kMaxClients = LiveChannel::kMaxClients;
  enum class Kind : uint8_t { Joined, Left, Text, TooLarge };
  struct Member {
    Kind kind;
    uint8_t client;
  };
  struct Message {
    Kind kind;  // Text or TooLarge
    uint8_t client;
    uint16_t len;
    char text[kMaxFrame + 1];
  };
  enum class Piece : uint8_t { More, Queued, TooLarge, Busy, Unknown };

  // --- the network task ---
  // A connection opened: its name, or 0 when `cap` clients are in (close it: 1013).
  uint8_t join(uint8_t cap) {
    uint8_t in = 0;
    Partial* free = nullptr;
    for (Partial& p : partial_) {
      if (p.name) in++;
      else if (!free) free = &p;
    }
    // Its Joined now, and room kept for its Left and for those of the clients already in.
    if (in >= cap || !free || members_.room() < 2 + in) return 0;
    uint8_t name;
    do name = next_ = static_cast<uint8_t>(next_ % 250 + 1);
    while (find(name));
    *free = Partial{name, 0, false};
    members_.push(Member{Kind::Joined, name});
    return name;
  }
  // Its connection closed: loop() is told (its place was kept by join()).
  void leave(uint8_t name) {
    Partial* p = name ? find(name) : nullptr;
    if (!p) return;
    p->name = 0;
    members_.push(Member{Kind::Left, name});
  }
  // A piece of a client's text message: `first` starts a message, `last` ends it. More: wait for
  // the rest. Queued/TooLarge: loop() has it. Busy: no room; the caller answers the client itself
  // (writeBusy) with what busyText() holds. Unknown: no such client.
  Piece received(uint8_t name, const char* data, size_t len, bool first, bool last) {
    Partial* p = name ? find(name) : nullptr;
    if (!p) return Piece::Unknown;
    if (first) p->got = 0, p->over = false;
    if (!p->over && p->got + len <= kMaxFrame) {
      memcpy(p->text + p->got, data, len);
      p->got = static_cast<uint16_t>(p->got + len);
    } else {
      p->over = true;
    }
    if (!last) return Piece::More;
    Message* m = messages_.claim();
    if (!m) {
      memcpy(busy_, p->text, p->over ? 0 : p->got);
      busyLen_ = p->over ? 0 : p->got;
      busy_[busyLen_] = 0;
      return Piece::Busy;
    }
    m->kind = p->over ? Kind::TooLarge : Kind::Text;
    m->client = name;
    m->len = p->over ? 0 : p->got;
    memcpy(m->text, p->text, m->len);
    m->text[m->len] = 0;
    messages_.publish();
    return p->over ? Piece::TooLarge : Piece::Queued;
  }
  // The message refused as Busy, to find its `id` in.
  const char* busyText() const { return busy_; }
  uint16_t busyLength() const { return busyLen_; }

  // --- loop() ---
  // Who joined and left first, then the messages: a client's Joined always comes before its
  // messages. A message from a client that has since left is still handed over: its line runs,
  // and its reply goes to a name nobody has.
  template <class OnMember, class OnMessage>
  void drain(OnMember onMember, OnMessage onMessage) {
    for (const Member* m; (m = members_.front()) != nullptr; members_.pop()) onMember(*m);
    for (const Message* m; (m = messages_.front()) != nullptr; messages_.pop()) onMessage(*m);
  }

 private:
  struct Partial {
    uint8_t name;  // 0: a free place
    uint16_t got;
    bool over;
    char text[kMaxFrame];
  };
  Partial* find(uint8_t name) {
    for (Partial& p : partial_)
      if (p.name == name) return &p;
    return nullptr;
  }

  SpscRing<Member, 16> members_;
  SpscRing<Message, 8> messages_;  // a burst of eight: the app sends a few at a time
  Partial partial_[kMaxClients] = {};
  uint8_t next_ = 0;
  char busy_[kMaxFrame + 1] = {};
  uint16_t busyLen_ = 0;
};

// The `busy` error the network task sends itself, with the refused `send`'s id when it had one.
inline void writeBusy(JsonWriter& w, bool hasId, int64_t id) {
  w.beginObject().key("type").string("error").key("code").string("busy").key("message").string("too many messages waiting for the ESP; try again");
  if (hasId) w.key("id").number(id);
  w.endObject();
}

}  // namespace esp
}  // namespace uv
