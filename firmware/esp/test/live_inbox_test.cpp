// Host tests of /ws's inbox (live_inbox.h): joins and leaves never lost, messages put together
// from pieces up to 256 bytes, `busy` when full, names never given again soon.
#include "live_inbox.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

using namespace uv::esp;

namespace {
struct Seen {
  std::vector<std::pair<LiveInbox::Kind, uint8_t>> members;
  std::vector<std::string> texts;
  std::vector<uint8_t> tooLarge;
  void drain(LiveInbox& in) {
    in.drain([&](const LiveInbox::Member& m) { members.emplace_back(m.kind, m.client); },
             [&](const LiveInbox::Message& m) {
               if (m.kind == LiveInbox::Kind::Text) texts.emplace_back(m.text, m.len);
               else tooLarge.push_back(m.client);
             });
  }
};
}  // namespace

TEST(LiveInbox, ClientsJoinUpToTheBoardsCapAndAreNamedAfresh) {
  LiveInbox in;
  std::set<uint8_t> names;
  for (int i = 0; i < 3; i++) names.insert(in.join(3));
  EXPECT_EQ(names.size(), 3u);
  EXPECT_EQ(names.count(0), 0u);
  EXPECT_EQ(in.join(3), 0);  // the ESP8266's cap: the fourth is closed 1013
  uint8_t first = *names.begin();
  in.leave(first);
  uint8_t again = in.join(3);
  EXPECT_NE(again, 0);
  EXPECT_EQ(names.count(again), 0u);  // a new name: what loop() still says to the old one goes nowhere
  Seen s;
  s.drain(in);
  EXPECT_EQ(s.members.size(), 5u);
  EXPECT_EQ(s.members[3], std::make_pair(LiveInbox::Kind::Left, first));
}

TEST(LiveInbox, JoinsAndLeavesAreNeverLostWhenMessagesFillIt) {
  LiveInbox in;
  Seen s;
  // Churn without loop() draining: every join that is let in has its Left kept.
  std::vector<uint8_t> in4;
  int refused = 0;
  for (int i = 0; i < 40; i++) {
    uint8_t n = in.join(4);
    if (!n) {
      refused++;
      if (!in4.empty()) in.leave(in4.front()), in4.erase(in4.begin());
      continue;
    }
    in4.push_back(n);
    for (int k = 0; k < 6; k++) in.received(n, "{}", 2, true, true);  // some are refused busy
  }
  EXPECT_GT(refused, 0);  // the ring filled: joins were refused, not leaves dropped
  for (uint8_t n : in4) in.leave(n);
  s.drain(in);
  int balance = 0;
  for (auto& m : s.members) balance += m.first == LiveInbox::Kind::Joined ? 1 : -1;
  EXPECT_EQ(balance, 0);  // every client that joined was seen to leave
}

TEST(LiveInbox, AMessageInPiecesIsPutTogetherUpTo256Bytes) {
  LiveInbox in;
  uint8_t a = in.join(4), b = in.join(4);
  std::string line = R"({"type":"send","line":"M115","id":7})";
  EXPECT_EQ(in.received(a, line.data(), 10, true, false), LiveInbox::Piece::More);
  EXPECT_EQ(in.received(b, "{\"type\":", 8, true, false), LiveInbox::Piece::More);  // interleaved
  EXPECT_EQ(in.received(a, line.data() + 10, line.size() - 10, false, true), LiveInbox::Piece::Queued);
  EXPECT_EQ(in.received(b, "\"ping\"}", 7, false, true), LiveInbox::Piece::Queued);
  std::string full(256, ' ');
  full[0] = '{', full[255] = '}';
  EXPECT_EQ(in.received(a, full.data(), 100, true, false), LiveInbox::Piece::More);
  EXPECT_EQ(in.received(a, full.data() + 100, 156, false, true), LiveInbox::Piece::Queued);
  Seen s;
  s.drain(in);
  ASSERT_EQ(s.texts.size(), 3u);
  EXPECT_EQ(s.texts[0], line);
  EXPECT_EQ(s.texts[1], R"({"type":"ping"})");
  EXPECT_EQ(s.texts[2], full);
  EXPECT_EQ(in.received(a, full.data(), 256, true, false), LiveInbox::Piece::More);
  EXPECT_EQ(in.received(a, "x", 1, false, true), LiveInbox::Piece::TooLarge);  // 257: refused whole
  s.drain(in);
  EXPECT_EQ(s.tooLarge, std::vector<uint8_t>{a});
  EXPECT_EQ(in.received(99, "{}", 2, true, true), LiveInbox::Piece::Unknown);
}

TEST(LiveInbox, AFullInboxAnswersBusyWithTheSendsId) {
  LiveInbox in;
  uint8_t a = in.join(4);
  std::string m = R"({"type":"send","line":"G28","id":42})";
  int queued = 0;
  while (in.received(a, m.data(), m.size(), true, true) == LiveInbox::Piece::Queued) queued++;
  EXPECT_EQ(queued, 8);
  ASSERT_EQ(std::string(in.busyText(), in.busyLength()), m);
  nlohmann::json j = nlohmann::json::parse(std::string(in.busyText(), in.busyLength()));
  char buf[160];
  JsonWriter w(buf, sizeof buf);
  writeBusy(w, j.contains("id"), j["id"].get<int64_t>());
  nlohmann::json busy = nlohmann::json::parse(w.text());
  EXPECT_EQ(busy["code"], "busy");
  EXPECT_EQ(busy["id"], 42);
  Seen s;
  s.drain(in);
  EXPECT_EQ(s.texts.size(), 8u);
  EXPECT_EQ(in.received(a, m.data(), m.size(), true, true), LiveInbox::Piece::Queued);  // room again
}
