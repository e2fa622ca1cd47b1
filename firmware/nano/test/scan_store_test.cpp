// Host tests of the scan-program buffers: loading, every seal verdict, the cap across a chain,
// and the events the timer gets, through continuations and underruns.
#include "scan_store.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

using namespace nano;
using uv::PassState;
using uv::SealCode;

namespace {

using Events = std::vector<std::pair<uint32_t, uint8_t>>;

uint16_t checkOf(const Events& ev) {
  uint16_t c = uv::kCheckInit;
  for (auto& e : ev) c = uv::checkEvent(c, e.first, e.second);
  return c;
}

struct Store {
  ScanStore s{10000000};
  bool line(const std::string& l) { return s.append(l.data(), static_cast<uint8_t>(l.size())); }
  // Loads the events in lines of `perLine` and seals them with the right count and check.
  SealCode load(const Events& ev, uint8_t flags, size_t perLine = 6) {
    for (size_t i = 0, q = 0; i < ev.size(); q++) {
      std::string l = "A:" + std::to_string(q);
      for (size_t k = 0; k < perLine && i < ev.size(); k++, i++) l += "," + std::to_string(ev[i].first) + "," + std::to_string(ev[i].second);
      line(l);
    }
    return s.seal({flags, static_cast<uint8_t>(ev.size()), checkOf(ev)});
  }
  Events drain() {
    Events out;
    uint32_t d;
    uint8_t m;
    while (s.next(d, m) == ScanStore::Step::Event) out.push_back({d, m});
    return out;
  }
};

}  // namespace

TEST(ScanStore, ArmsAProgramAndHandsOutItsEvents) {
  Store t;
  Events ev = {{0, 1}, {2000, 0}, {10, 5}, {1990, 4}, {1, 0}};
  EXPECT_EQ(t.s.freeBuffers(), 2);
  EXPECT_EQ(t.load(ev, 0, 2), SealCode::Armed);
  EXPECT_EQ(t.s.armed(), 1);
  EXPECT_EQ(t.s.freeBuffers(), 1);
  ASSERT_TRUE(t.s.startable());
  t.s.start();
  EXPECT_EQ(t.s.pass(), PassState::Running);
  EXPECT_EQ(t.drain(), ev);
  EXPECT_EQ(t.s.pass(), PassState::Whole);
  EXPECT_FALSE(t.s.running());
  EXPECT_EQ(t.s.freeBuffers(), 1);  // spent: kept for the dose tally until it has read it
  ScanStore::ProgramView v;
  ASSERT_TRUE(t.s.oldestSpent(v));
  EXPECT_EQ(v.count, ev.size());
  EXPECT_EQ(v.words[1], 2000u << 4);
  t.s.freeOldestSpent();
  EXPECT_FALSE(t.s.oldestSpent(v));
  EXPECT_EQ(t.s.freeBuffers(), 2);
}

TEST(ScanStore, ChainsContinuationsLoadedWhileTheFirstRuns) {
  Store t;
  Events a = {{100, 3}, {500, 1}}, b = {{700, 0}, {300, 8}}, c = {{40, 0}};
  ASSERT_EQ(t.load(a, uv::kSealMore), SealCode::Armed);
  t.s.start();
  uint32_t d;
  uint8_t m;
  ASSERT_EQ(t.s.next(d, m), ScanStore::Step::Event);  // the first program runs
  ASSERT_EQ(t.load(b, uv::kSealContinuation | uv::kSealMore), SealCode::Armed);
  EXPECT_EQ(t.s.freeBuffers(), 0);
  ASSERT_EQ(t.s.next(d, m), ScanStore::Step::Event);
  ASSERT_EQ(t.s.next(d, m), ScanStore::Step::Event);  // b's first: its buffer took over
  EXPECT_EQ(d, 700u);
  ScanStore::ProgramView v;
  uint8_t made;
  ASSERT_TRUE(t.s.runningProgram(v, made));
  EXPECT_EQ(made, 0u);                               // b's first is taken, not yet made
  EXPECT_EQ(t.s.freeBuffers(), 0);                   // a's buffer is spent,
  t.s.freeOldestSpent();
  EXPECT_EQ(t.s.freeBuffers(), 1);                   // and free again once the tally has read it
  ASSERT_EQ(t.load(c, uv::kSealContinuation), SealCode::Armed);
  EXPECT_EQ(t.drain(), (Events{{300, 8}, {40, 0}}));
  EXPECT_EQ(t.s.pass(), PassState::Whole);
}

TEST(ScanStore, AChainWhoseNextIsNotArmedInTimeIsCutShort) {
  Store t;
  ASSERT_EQ(t.load({{0, 1}, {100, 3}}, uv::kSealMore), SealCode::Armed);
  t.s.start();
  uint32_t d;
  uint8_t m;
  t.s.next(d, m);
  t.s.next(d, m);
  EXPECT_EQ(t.s.next(d, m), ScanStore::Step::Underrun);
  EXPECT_EQ(t.s.pass(), PassState::Underrun);
  // A continuation that comes now has nothing to continue.
  EXPECT_EQ(t.load({{5, 0}}, uv::kSealContinuation), SealCode::BadStart);
}

TEST(ScanStore, RefusesEverySpoiledOrWrongProgram) {
  Store t;
  EXPECT_EQ(t.s.seal({0, 1, 0}), SealCode::NoLoad);  // nothing loaded
  // A line out of sequence spoils the load; the rest of its lines are dropped.
  t.line("A:0,0,1");
  t.line("A:2,5,0");
  EXPECT_EQ(t.s.seal({0, 2, checkOf({{0, 1}, {5, 0}})}), SealCode::NoLoad);
  // A malformed A line: false (the Nano latches MALFORMED) and the load is spoiled.
  t.line("A:0,0,1");
  EXPECT_FALSE(t.line("A:1,5,16"));
  EXPECT_FALSE(t.line("A:1,5"));
  EXPECT_FALSE(t.line("A:1"));
  EXPECT_EQ(t.s.seal({0, 1, checkOf({{0, 1}})}), SealCode::NoLoad);
  // Count and check must match what arrived.
  t.line("A:0,0,1,5,0");
  EXPECT_EQ(t.s.seal({0, 1, checkOf({{0, 1}, {5, 0}})}), SealCode::Mismatch);
  t.line("A:0,0,1,5,0");
  EXPECT_EQ(t.s.seal({0, 2, static_cast<uint16_t>(checkOf({{0, 1}, {5, 0}}) ^ 1)}), SealCode::Mismatch);
  // The last program of a chain may not leave an LED on.
  EXPECT_EQ(t.load({{0, 1}, {5, 2}}, 0), SealCode::EndsLit);
  // Over 64 events.
  Events many;
  for (int i = 0; i < 65; i++) many.push_back({i ? 10u : 0u, static_cast<uint8_t>(i & 1)});
  EXPECT_EQ(t.load(many, 0), SealCode::TooMany);
  // A continuation of nothing, and a first program with a zero-delay start as a continuation.
  EXPECT_EQ(t.load({{5, 0}}, uv::kSealContinuation), SealCode::BadStart);
  ASSERT_EQ(t.load({{0, 1}}, uv::kSealMore), SealCode::Armed);
  EXPECT_EQ(t.load({{0, 0}}, uv::kSealContinuation), SealCode::BadStart);
  EXPECT_EQ(t.load({{0, 1}, {5, 0}}, 0), SealCode::BadStart);  // the chain waits for its continuation
  ASSERT_EQ(t.load({{5, 0}}, uv::kSealContinuation), SealCode::Armed);
  // Both buffers hold armed programs: an A:0 finds none free.
  t.line("A:0,0,1,5,0");
  EXPECT_EQ(t.s.seal({0, 2, checkOf({{0, 1}, {5, 0}})}), SealCode::NoBuffer);
  EXPECT_EQ(t.s.seal({0, 2, checkOf({{0, 1}, {5, 0}})}), SealCode::NoLoad);  // the reason is told once
  EXPECT_EQ(t.s.armed(), 2);
}

TEST(ScanStore, HoldsTheExposureCapAcrossTheChain) {
  ScanStore s(1000);
  auto load = [&](const Events& ev, uint8_t flags) {
    std::string l = "A:0";
    for (auto& e : ev) l += "," + std::to_string(e.first) + "," + std::to_string(e.second);
    s.append(l.data(), static_cast<uint8_t>(l.size()));
    return s.seal({flags, static_cast<uint8_t>(ev.size()), checkOf(ev)});
  };
  EXPECT_EQ(load({{0, 1}, {1000, 0}}, 0), SealCode::Armed);  // exactly the cap
  s.discard(PassState::CutByReset);
  EXPECT_EQ(load({{0, 1}, {1001, 0}}, 0), SealCode::Capped);
  // LED 0 on for 600 µs at the end of one program and 401 more in the next: 1001 in one stretch.
  ASSERT_EQ(load({{0, 1}, {600, 1}}, uv::kSealMore), SealCode::Armed);
  EXPECT_EQ(load({{401, 0}}, uv::kSealContinuation), SealCode::Capped);
  EXPECT_EQ(load({{400, 0}}, uv::kSealContinuation), SealCode::Armed);
  // Switching LED 1 while LED 0 stays on does not restart LED 0's stretch.
  s.discard(PassState::CutByReset);
  EXPECT_EQ(load({{0, 1}, {500, 3}, {501, 1}, {1, 0}}, 0), SealCode::Capped);
}

TEST(ScanStore, DiscardCutsARunningChainAndFreesBothBuffers) {
  Store t;
  ASSERT_EQ(t.load({{0, 1}, {100, 0}}, 0), SealCode::Armed);
  ASSERT_EQ(t.load({{0, 2}, {100, 0}}, 0), SealCode::Armed);
  t.s.start();
  t.s.discard(PassState::CutByFault);
  EXPECT_EQ(t.s.pass(), PassState::CutByFault);
  EXPECT_EQ(t.s.freeBuffers(), 2);
  EXPECT_FALSE(t.s.startable());
  uint32_t d;
  uint8_t m;
  EXPECT_EQ(t.s.next(d, m), ScanStore::Step::End);
}

TEST(ScanStore, ArmedProgramsStartInTheOrderSealed) {
  Store t;
  ASSERT_EQ(t.load({{0, 1}, {100, 0}}, 0), SealCode::Armed);
  ASSERT_EQ(t.load({{0, 2}, {100, 0}}, 0), SealCode::Armed);
  t.s.start();
  EXPECT_EQ(t.drain(), (Events{{0, 1}, {100, 0}}));
  ASSERT_TRUE(t.s.startable());
  t.s.start();
  EXPECT_EQ(t.drain(), (Events{{0, 2}, {100, 0}}));
}

// B lines (nano.md "B:q,<packed>") load what A lines do, and a malformed or overfull one leaves
// nothing behind: the load is spoiled, and the program never arms.
TEST(ScanStore, PackedLinesLoadLikeAppendLines) {
  Events ev;
  for (uint32_t i = 0; i < 64; i++) ev.push_back({i ? 3 + i * 97 % 5000 : 0, static_cast<uint8_t>(i % 16 % 15)});
  auto packedLine = [&](size_t q, size_t from, size_t to) {
    std::string l = "B:" + std::to_string(q) + ",";
    char w[uv::kPackMaxChars];
    for (size_t i = from; i < to; i++) l.append(w, uv::packWord(ev[i].first << 4 | ev[i].second, w));
    return l;
  };
  Store u;
  ASSERT_TRUE(u.line(packedLine(0, 0, 30)));
  ASSERT_TRUE(u.line(packedLine(1, 30, 64)));
  ASSERT_EQ(u.s.seal({0, 64, checkOf(ev)}), SealCode::Armed);
  u.s.start();
  EXPECT_EQ(u.drain(), ev);

  Store bad;
  bad.line(packedLine(0, 0, 10));
  EXPECT_FALSE(bad.line("B:1,_?"));  // a leading zero group
  EXPECT_EQ(bad.s.seal({0, 10, 0}), SealCode::NoLoad);
  EXPECT_EQ(bad.s.freeBuffers(), 2);
  bad.line(packedLine(0, 0, 60));
  EXPECT_TRUE(bad.line(packedLine(1, 0, 5)));  // 65 events
  EXPECT_EQ(bad.s.seal({0, 64, 0}), SealCode::TooMany);
}
