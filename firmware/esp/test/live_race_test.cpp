// /ws with both sides running at once, as on the ESP32's two cores: a network thread (the only
// one that touches the connections) lets clients join, send messages in pieces and leave at
// every step, pumps the live channel to them and takes what each connection can hold only when
// its queue is empty; a loop thread drains the inbox and writes to the channel: greetings,
// echoes and a stream of broadcasts, some large, so the ring wraps and a slow client falls a ring
// behind. The only things shared are the inbox's rings and the channel's ring. Built with
// ThreadSanitizer (esp_race_tests, scripts/tsan.sh), a torn message, one delivered to the wrong
// client, before its hello or out of order, or a join or leave lost fails the run.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "live_channel.h"
#include "live_inbox.h"

using namespace uv::esp;

namespace {

// {"to":T,"n":N,"sum":S,"pad":"..."}: S is the pad's length times 31 plus N, so a torn copy shows.
std::string makeMessage(uint8_t to, uint32_t n, size_t pad) {
  char head[64];
  snprintf(head, sizeof head, "{\"to\":%u,\"n\":%u,\"sum\":%lu,\"pad\":\"", to, n, static_cast<unsigned long>(pad * 31 + n));
  return head + std::string(pad, static_cast<char>('a' + n % 26)) + "\"}";
}
bool checkMessage(const std::string& m, unsigned& to, unsigned& n) {
  unsigned long sum = 0;
  if (sscanf(m.c_str(), "{\"to\":%u,\"n\":%u,\"sum\":%lu,\"pad\":\"", &to, &n, &sum) != 3) return false;
  size_t start = m.find("\"pad\":\"") + 7, end = m.rfind("\"}");
  if (end == std::string::npos || end < start || end + 2 != m.size()) return false;
  size_t pad = end - start;
  for (size_t i = start; i < end; i++)
    if (m[i] != static_cast<char>('a' + n % 26)) return false;
  return sum == pad * 31 + n;
}

struct Connection {
  uint8_t name = 0;
  bool slow = false;                 // takes a frame off its queue rarely
  std::vector<std::string> queue;    // the library's per-client queue
  uint32_t lastEveryone = 0, lastOwn = 0;
  bool closed = false;
};

struct Connections : LiveClients {
  std::map<uint8_t, Connection> open;
  size_t queueLimit = 8;  // WS_MAX_QUEUED_MESSAGES on the ESP8266
  size_t maxQueued = 0;
  int closedSlow = 0, delivered = 0, bad = 0;
  std::thread::id owner;
  bool trySend(uint8_t client, const char* text, uint16_t len) override {
    EXPECT_EQ(std::this_thread::get_id(), owner);
    auto it = open.find(client);
    if (it == open.end()) return true;  // gone
    if (!it->second.queue.empty()) return false;  // only when its queue is empty: one copy on the heap
    it->second.queue.emplace_back(text, len);
    maxQueued = std::max(maxQueued, it->second.queue.size());
    EXPECT_LE(it->second.queue.size(), queueLimit);
    return true;
  }
  void close(uint8_t client, uint16_t code, const char*) override {
    EXPECT_EQ(std::this_thread::get_id(), owner);
    auto it = open.find(client);
    if (it == open.end()) return;
    EXPECT_EQ(code, 1008);
    it->second.closed = true;
    closedSlow++;
  }
  // The connection's peer reads one frame: it must be whole, its own, and in order.
  void take(Connection& c) {
    if (c.queue.empty()) return;
    std::string m = c.queue.front();
    c.queue.erase(c.queue.begin());
    unsigned to = 0, n = 0;
    if (!checkMessage(m, to, n)) {
      ADD_FAILURE() << "torn: " << m.substr(0, 80);
      bad++;
      return;
    }
    delivered++;
    if (!c.lastOwn && to == LiveChannel::kEveryone) {
      ADD_FAILURE() << "a broadcast before the client's hello";
      bad++;
      return;
    }
    if (to == LiveChannel::kEveryone) {
      EXPECT_GT(n, c.lastEveryone) << "out of order";
      c.lastEveryone = n;
    } else {
      EXPECT_EQ(to, c.name) << "another client's message";
      EXPECT_GT(n, c.lastOwn) << "out of order";
      c.lastOwn = n;
    }
  }
};

}  // namespace

TEST(LiveRace, ClientsComeAndGoWhileLoopWritesAndNothingTornOrLost) {
  Connections conns;
  LiveChannel live(conns);
  LiveInbox inbox;
  std::atomic<bool> done{false};
  std::atomic<int> loopMembers{0};
  std::atomic<uint32_t> broadcasts{0};
  int joins = 0, leaves = 0, sent = 0, busy = 0;

  std::thread loopThread([&] {
    std::mt19937 rng(5);
    std::set<uint8_t> members;
    std::map<uint8_t, uint32_t> own;
    uint32_t everyone = 0;
    auto drain = [&] {
      inbox.drain(
          [&](const LiveInbox::Member& m) {
            if (m.kind == LiveInbox::Kind::Joined) {
              EXPECT_TRUE(members.insert(m.client).second) << "joined twice";
              std::string hello = makeMessage(m.client, ++own[m.client], 20);
              live.sendTo(m.client, hello.c_str(), static_cast<uint16_t>(hello.size()));
            } else {
              EXPECT_EQ(members.erase(m.client), 1u) << "left without joining";
            }
          },
          [&](const LiveInbox::Message& m) {
            EXPECT_EQ(m.kind, LiveInbox::Kind::Text);
            std::string echo = makeMessage(m.client, ++own[m.client], m.len);
            live.sendTo(m.client, echo.c_str(), static_cast<uint16_t>(echo.size()));
          });
      loopMembers.store(static_cast<int>(members.size()));
    };
    while (!done.load(std::memory_order_acquire)) {
      drain();
      size_t pad = rng() % 5 == 0 ? 1500 + rng() % 500 : rng() % 120;
      std::string b = makeMessage(LiveChannel::kEveryone, ++everyone, pad);
      live.broadcast(b.c_str(), static_cast<uint16_t>(b.size()));
      broadcasts.store(everyone, std::memory_order_relaxed);
      (void)live.count();
      std::this_thread::yield();
    }
    for (int i = 0; i < 3; i++) drain();
  });

  conns.owner = std::this_thread::get_id();
  std::mt19937 rng(17);
  // Until both sides have done enough, however the two threads are scheduled on a busy machine.
  for (long step = 0; (broadcasts.load() < 20000 || joins < 300 || conns.delivered < 3000 || conns.closedSlow < 5) && step < 20'000'000; step++) {
    if (step % 64 == 0) std::this_thread::yield();
    unsigned what = rng() % 16;
    if (what == 0 && conns.open.size() < LiveChannel::kMaxClients) {
      uint8_t name = inbox.join(LiveChannel::kMaxClients);
      if (name && live.join(name)) {
        Connection c;
        c.name = name;
        c.slow = rng() % 4 == 0;
        conns.open[name] = c;
        joins++;
      } else if (name) {
        inbox.leave(name);
      }
    } else if (what == 1 && !conns.open.empty()) {  // a client leaves, at whatever step it is in
      auto it = std::next(conns.open.begin(), static_cast<long>(rng() % conns.open.size()));
      live.leave(it->first);
      inbox.leave(it->first);
      conns.open.erase(it);
      leaves++;
    } else if (what <= 4 && !conns.open.empty()) {  // a message, maybe in pieces
      auto it = std::next(conns.open.begin(), static_cast<long>(rng() % conns.open.size()));
      std::string m = std::string(1 + rng() % 200, 'm');
      size_t cut = rng() % m.size();
      if (cut) inbox.received(it->first, m.data(), cut, true, false);
      LiveInbox::Piece p = inbox.received(it->first, m.data() + cut, m.size() - cut, cut == 0, true);
      if (p == LiveInbox::Piece::Busy) busy++;
      else sent++;
    } else {
      for (auto& [name, c] : conns.open)
        if (!c.slow || rng() % 50 == 0) conns.take(c);
      live.pump();
      // A connection closed as too slow goes: its disconnect.
      for (auto it = conns.open.begin(); it != conns.open.end();) {
        if (it->second.closed) {
          live.leave(it->first);
          inbox.leave(it->first);
          it = conns.open.erase(it);
          leaves++;
        } else {
          ++it;
        }
      }
    }
  }
  for (auto& [name, c] : conns.open) {
    live.leave(name);
    inbox.leave(name);
    leaves++;
  }
  conns.open.clear();
  done.store(true, std::memory_order_release);
  loopThread.join();
  std::printf("[esp live] %d joins, %d leaves, %d client messages (%d answered busy), %d frames delivered whole, %d clients closed as a ring behind, at most %zu frame queued a client\n",
              joins, leaves, sent, busy, conns.delivered, conns.closedSlow, conns.maxQueued);
  EXPECT_EQ(loopMembers.load(), 0);  // every join and leave reached loop()
  EXPECT_EQ(conns.bad, 0);
  EXPECT_EQ(joins, leaves);
  EXPECT_GT(joins, 100);
  EXPECT_GT(conns.delivered, 1000);
  EXPECT_GT(conns.closedSlow, 0);
  EXPECT_EQ(conns.maxQueued, 1u);
}
