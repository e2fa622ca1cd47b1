// The Mega's printhead link loading and running a scan chain (protocol/nano.md "Scan programs")
// against the real Nano logic: two programs before the start, the rest as buffers free up while it
// runs, a Q poll every 10 ms; the light comes out at the events' times after the G's time 0.
#include <gtest/gtest.h>

#include <vector>

#include "fake_nano.h"
#include "grid_cells.h"
#include "printhead_link.h"
#include "scan.h"
#include "scan_program.h"

using namespace mega;

namespace {

using Events = std::vector<std::pair<uint32_t, uint8_t>>;

struct Chain : ::testing::Test {
  FakeNano nano;
  PrintheadLink link{nano};
  uint32_t now = 0;
  Events events;
  size_t taken = 0;
  uv::ProgramLines lines{[](void* ctx, uint32_t& t, uint8_t& m) {
                           auto* c = static_cast<Chain*>(ctx);
                           if (c->taken == c->events.size()) return false;
                           t = c->events[c->taken].first;
                           m = c->events[c->taken++].second;
                           return true;
                         },
                         this};
  char line[uv::kNanoMaxLine + 2];
  uint8_t held = 0;        // a line taken from the writer, not yet sent
  uint16_t sealed = 0;     // K answers 0

  void SetUp() override {
    link.begin(now);
    step(600000);
  }
  void step(uint32_t us) {
    for (uint32_t end = now + us; now < end; now += 100) {
      nano.advance(now);
      link.poll(now);
    }
  }
  // Sends the next program's lines and waits for its K answer; false at the end of the chain.
  bool loadProgram() {
    for (;;) {
      if (!held && !(held = lines.next(line))) return false;
      int tries = 0;
      while (!link.programLine(line, held, now)) {
        step(100);
        if (++tries == 1000) { ADD_FAILURE() << "cannot send " << line; return false; }
      }
      const bool seal = line[0] == 'K';
      held = 0;
      if (!seal) continue;
      for (int i = 0; !link.sealAnswered(); i++) {
        step(100);
        if (i == 1000) { ADD_FAILURE() << "no K answer; nano got " << nano.lines.back(); return false; }
      }
      EXPECT_EQ(link.sealCode(), 0);
      sealed++;
      return true;
    }
  }
  uint8_t poll() {
    link.requestPass();
    while (!link.passAnswered()) step(100);
    return link.passState();
  }
};

// A pass as the scan planner makes it (ScanPlanner::nextEvent): 2 ms windows, each of the four
// LEDs on its own row, gray cells of 14-99 % centred in theirs, some windows dark.
Events pass(uint16_t windows) {
  uv::JobHeader h{};
  h.cols = windows;
  h.rows = 4;
  h.pitchUm[0] = h.pitchUm[1] = 50;
  h.originUm[0] = 1000;
  h.originUm[1] = 2000;
  h.map = uv::DoseMap::Linear;
  h.fullUs = 2000;
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(windows, 0));
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k);
    for (int j = 0; j < windows; j++)
      if ((j * 7 + k * 3) % 5) rows[k][j] = static_cast<uint8_t>(36 * (1 + (j + k) % 7));
  }
  const uv::MotionModel machine{{150000, 100000}, {3000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
  uvtest::GridCells cells(rows);
  uv::ScanPlanner planner(h, cells, machine);
  uv::ScanPass p;
  Events ev;
  if (!planner.nextPass(p)) return ev;
  uint32_t t;
  uint8_t m;
  while (planner.nextEvent(t, m)) ev.push_back({t, m});
  return ev;
}

}  // namespace

TEST_F(Chain, LoadsTwoProgramsThenTheRestWhileItRunsAndTheLightFollowsTheEvents) {
  events = pass(60);  // 0.12 s, about 6 programs
  ASSERT_TRUE(loadProgram());
  ASSERT_TRUE(loadProgram());
  ASSERT_TRUE(link.startChain());
  step(100);
  const uint32_t time0 = nano.nowUs + uv::kProgramStartLeadUs - 100;  // the G reached the fake at once
  uint32_t nextPoll = now;
  for (;;) {
    if (now >= nextPoll) {
      uint8_t state = poll();
      nextPoll = now + 10000;
      if (state != static_cast<uint8_t>(uv::PassState::Running)) {
        EXPECT_EQ(state, static_cast<uint8_t>(uv::PassState::Whole));
        break;
      }
      // Each program sealed takes a buffer: the count from the last Q goes down with it.
      for (uint8_t free = link.passFree(); free > 0 && loadProgram(); free--) {
      }
    }
    step(100);
  }
  EXPECT_GE(sealed, 5);
  // Every LED's light against the events.
  for (uint8_t k = 0; k < 4; k++) {
    std::vector<std::pair<uint64_t, uint64_t>> want, got;
    bool on = false;
    uint32_t since = 0;
    for (auto& e : events) {
      bool is = e.second >> k & 1;
      if (is && !on) since = e.first;
      if (!is && on) want.push_back({time0 + since, time0 + e.first});
      on = is;
    }
    for (auto& l : nano.scanLight)
      if (l.led == k) got.push_back({l.onUs, l.offUs});
    // The fake runs events on its 100 µs steps: each edge within one step of its time.
    ASSERT_EQ(got.size(), want.size()) << "LED " << int(k);
    for (size_t i = 0; i < got.size(); i++) {
      EXPECT_NEAR(got[i].first, want[i].first, 100) << "LED " << int(k) << " interval " << i;
      EXPECT_NEAR(got[i].second, want[i].second, 100) << "LED " << int(k) << " interval " << i;
    }
  }
  EXPECT_EQ(nano.lit(), 0);
}

TEST_F(Chain, AChainTheMegaStopsFeedingEndsCutAndDark) {
  events = pass(200);  // far more than two programs
  ASSERT_TRUE(loadProgram());
  ASSERT_TRUE(loadProgram());
  ASSERT_TRUE(link.startChain());
  uint32_t nextPoll = now;
  uint8_t state = 0;
  while (now < 1000000) {
    if (now >= nextPoll) {
      state = poll();  // polled, but never fed again
      nextPoll = now + 10000;
      if (state != static_cast<uint8_t>(uv::PassState::Running)) break;
    }
    step(100);
  }
  EXPECT_EQ(state, static_cast<uint8_t>(uv::PassState::Underrun));
  EXPECT_EQ(nano.lit(), 0);
}
