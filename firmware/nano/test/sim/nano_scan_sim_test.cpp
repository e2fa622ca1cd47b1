// Runs build/avr/nano.elf in simavr and measures scan programs on its pins (protocol/nano.md
// "Scan programs"): every LED edge against its event's time after the `\n` of `G`, a chain loaded
// while it runs, and the cuts (an underrun, R).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "nano_sim_fixture.h"

namespace {

struct ScanBudget {
  double edgeErrorUs = 0, startErrorUs = 0, interruptsOffUs = 0, sealReplyUs = 0, silenceCutMs = 0, behindPackedUs = -1, behindAppendUs = -1;
  int edges = 0, starts = 0;
  std::vector<std::pair<uint32_t, double>> closeLate;  // two events this many µs apart: the second's lateness
  ~ScanBudget() {
    std::printf("[nano budget] scan program: time 0 off the G's newline + 1000 us, worst of %d starts: %.3f us (budget 20 us)\n",
                starts, startErrorUs);
    std::printf("[nano budget] scan program: worst LED edge off its time after time 0, of %d edges: %.3f us (budget 1 us)\n",
                edges, edgeErrorUs);
    std::printf("[nano budget] scan program: longest interrupts-off window while a chain runs: %.1f us\n", interruptsOffUs);
    std::printf("[nano budget] scan program: K answered, worst: %.1f us after its newline (budget 2000 us)\n", sealReplyUs);
    std::printf("[nano budget] scan program: a chain cut %.1f ms after the Mega's last line (rule: 50 ms)\n", silenceCutMs);
    std::printf("[nano budget] scan program: a Q right behind the longest load line answered %.1f us after its newline (a B line of 59 events; "
                "%.1f us behind an A line of 15)\n", behindPackedUs, behindAppendUs);
    if (!closeLate.empty()) {
      std::printf("[nano budget] scan program: the second of two events close together comes late by");
      for (auto& c : closeLate) std::printf(" %.1f us (%u us apart)", c.second, c.first);
      std::printf("\n");
    }
  }
} budget;


// A pass as the scan planner lays it out: windows of W µs, each LED's cells centred in theirs.
// gray: every level; else PCB-like runs of full cells (W = full dose, so runs merge).
Events passEvents(int windows, uint32_t W, bool gray) {
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> leds(4);
  for (int k = 0; k < 4; k++)
    for (int j = 0; j < windows; j++) {
      int v = (j * 37 + k * 11) % 7;
      bool lit = gray ? v != 0 : (j / (3 + k)) % 2 == 0;
      if (!lit) continue;
      uint32_t t = gray ? (v == 6 ? W : v * (W / 8) + k) : W;
      uint32_t on = j * W + (W - t) / 2;
      if (!leds[k].empty() && leds[k].back().second == on) leds[k].back().second = on + t;
      else leds[k].push_back({on, on + t});
    }
  std::vector<uint32_t> times;
  for (auto& l : leds)
    for (auto& iv : l) times.insert(times.end(), {iv.first, iv.second});
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  Events ev;
  for (uint32_t t : times) {
    uint8_t m = 0;
    for (int k = 0; k < 4; k++)
      for (auto& iv : leds[k])
        if (iv.first <= t && t < iv.second) m |= 1 << k;
    ev.push_back({t, m});
  }
  return ev;
}

// Loads one program and waits for its K reply, timing the reply from the K's newline.
std::string load(NanoRig& rig, const std::string& program) {
  rig.takeLines();
  rig.lineEnds.clear();
  size_t out = rig.output.size();
  rig.send(program);
  std::string got;
  rig.runUntil([&] {
    for (auto& l : rig.takeLines())
      if (l[0] == 'K') got = l;
    return !got.empty();
  }, 200000);
  for (size_t i = out; i < rig.output.size(); i++)
    if (rig.output[i].c == 'K') {
      double latency = us(rig.output[i].cycle - rig.lineEnds.back());
      budget.sealReplyUs = std::max(budget.sealReplyUs, latency);
      EXPECT_LT(latency, 2000.0) << "K answered late";
      break;
    }
  return got;
}

// Sends G and returns the cycle its '\n' arrived at: time 0 is 1000 µs later.
uint64_t start(NanoRig& rig) {
  rig.lineEnds.clear();
  rig.send("G\n");
  rig.runUntil([&] { return !rig.lineEnds.empty(); }, 1000);
  return rig.lineEnds.front();
}

// Compares every LED edge after `gCycle` with the events. Time 0 itself lands a few µs after its
// nominal moment, by however long another interrupt held up the one that timed the `\n`; each edge
// is measured from it, and the start from its nominal moment.
void checkEdges(NanoRig& rig, const Events& ev, uint64_t gCycle) {
  double time0 = us(gCycle) + uv::kProgramStartLeadUs, worst = 0, start = NAN;
  int n = 0;
  for (int k = 0; k < 4; k++) {
    std::vector<std::pair<double, bool>> want;
    bool was = false;
    for (auto& e : ev) {
      bool is = e.second >> k & 1;
      if (is != was) want.push_back({time0 + e.first, is});
      was = is;
    }
    std::vector<NanoRig::Edge> got;
    for (auto& e : rig.edges('B', 2 + k))
      if (e.cycle > gCycle) got.push_back(e);
    EXPECT_EQ(got.size(), want.size()) << "LED " << k;
    for (size_t i = 0; i < std::min(got.size(), want.size()); i++) {
      EXPECT_EQ(got[i].high, want[i].second) << "LED " << k << " edge " << i;
      double err = us(got[i].cycle) - want[i].first;
      if (std::isnan(start)) start = err;  // the chain's own time 0, from its first edge
      worst = std::max(worst, std::fabs(err - start));
      n++;
      EXPECT_LE(std::fabs(err - start), 1.0) << "LED " << k << " edge " << i << " at " << want[i].first - time0 << " us";
      if (getenv("NANO_SIM_VERBOSE")) std::printf("LED %d edge at %.0f us: %+.4f\n", k, want[i].first - time0, err - start);
    }
  }
  EXPECT_LE(std::fabs(start), 20.0) << "time 0 off its nominal moment";
  budget.edges += n;
  budget.starts++;
  budget.startErrorUs = std::max(budget.startErrorUs, std::fabs(start));
  budget.edgeErrorUs = std::max(budget.edgeErrorUs, worst);
}

// Runs for `us`, a Q poll every 20 ms as a Mega running a pass sends them.
void runPolling(NanoRig& rig, double us) {
  for (double t = 0; t < us; t += 20000) {
    rig.send("Q\n");
    rig.runUs(std::min(20000.0, us - t));
  }
}

void noteInterrupts(const NanoRig& rig) {
  double off = us(rig.maxInterruptsOff);
  budget.interruptsOffUs = std::max(budget.interruptsOffUs, off);
  EXPECT_LT(off, kByteTimeUs) << "interrupts off long enough to lose a received byte";
}

}  // namespace

TEST(NanoScanSim, EveryEdgeOfAGrayPassLandsOnItsTime) {
  auto rig = bootedRig();
  Events ev = passEvents(18, 2000, true);
  auto chain = programs(ev);
  ASSERT_EQ(chain.size(), 2u);  // both buffers hold it before the start
  for (auto& p : chain) ASSERT_EQ(load(*rig, p), "K:0");
  EXPECT_EQ(reply(*rig, "Q"), "Q:0,2,0");
  rig->clearEdges();
  rig->resetInterruptStats();
  uint64_t g = start(*rig);
  // Polls during the pass, as the Mega makes them.
  for (int i = 0; i < 30; i++) rig->send("S\nT\n");
  rig->runUs(uv::kProgramStartLeadUs + ev.back().first + 2000);
  checkEdges(*rig, ev, g);
  noteInterrupts(*rig);
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,2");
  EXPECT_EQ(reply(*rig, "C").substr(1), ":0,1,1");  // this start, one exposure, whole
}

TEST(NanoScanSim, AChainLoadedWhileItRunsLandsOnItsTimes) {
  auto rig = bootedRig();
  Events ev = passEvents(400, 2000, false);  // a PCB-like pass: runs of full cells, 0.8 s
  auto chain = programs(ev);
  ASSERT_GE(chain.size(), 3u);
  ASSERT_EQ(load(*rig, chain[0]), "K:0");
  rig->clearEdges();
  rig->resetInterruptStats();
  uint64_t g = start(*rig);
  // As the Mega does: each next program as soon as a buffer is free.
  for (size_t i = 1; i < chain.size(); i++) {
    ASSERT_TRUE(rig->runUntil([&] { return reply(*rig, "Q")[2] != '0'; }, 2e6)) << "program " << i;
    ASSERT_EQ(load(*rig, chain[i]), "K:0") << "program " << i;
  }
  rig->runUntil([&] { return reply(*rig, "Q") == "Q:2,0,2"; }, 2e6);
  checkEdges(*rig, ev, g);
  noteInterrupts(*rig);
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,2");
}

// The main loop parses a load line whole before it reads the next: a Q sent right behind the
// heaviest B line (59 one-character events, each stored and checked) waits for it. Measured 1168 us,
// 831 us behind an A line of 15 events, 90 us behind a B line of one (a typical photo line, 25
// events, about 500 us): within the K's 2000 us, and the receive ring's 64 bytes hold 5.5 ms of
// line. The Mega's relay never waits behind one: it asks Q for a free buffer when it has no line
// to send (planner.md "The printhead link").
TEST(NanoScanSim, AQRightBehindTheLongestLoadLineIsAnsweredPromptly) {
  auto rig = bootedRig();
  std::string decimal = "A:0";
  while (decimal.size() + 4 <= uv::kNanoMaxLine) decimal += ",1,1";
  const std::string packed = "B:0," + std::string(59, 'N');  // the word 15 (d 0, every LED) 59 times
  ASSERT_EQ(packed.size(), uv::kNanoMaxLine);
  for (double* figure : {&budget.behindPackedUs, &budget.behindAppendUs}) {
    rig->takeLines();
    rig->lineEnds.clear();
    const size_t out = rig->output.size();
    rig->send((figure == &budget.behindPackedUs ? packed : decimal) + "\nQ\n");
    ASSERT_TRUE(rig->runUntil([&] {
      for (auto& l : rig->takeLines())
        if (l[0] == 'Q') return true;
      return false;
    }, 100000));
    for (size_t i = out; i < rig->output.size(); i++)
      if (rig->output[i].c == 'Q') {
        *figure = us(rig->output[i].cycle - rig->lineEnds.at(1));
        break;
      }
    EXPECT_LT(*figure, 2000.0);
  }
  EXPECT_EQ(reply(*rig, "E"), "E:0");  // neither line was malformed
}

TEST(NanoScanSim, AContinuationNotArmedInTimeCutsThePass) {
  auto rig = bootedRig();
  Events ev = passEvents(400, 2000, false);
  auto chain = programs(ev);
  ASSERT_EQ(load(*rig, chain[0]), "K:0");
  rig->clearEdges();
  uint64_t g = start(*rig);
  runPolling(*rig, uv::kProgramStartLeadUs + ev[63].first + 100);  // the first program's last event
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,5");
  for (int k = 0; k < 4; k++) EXPECT_FALSE(rig->level('B', 2 + k)) << "LED " << k << " left on";
  EXPECT_EQ(reply(*rig, "C").substr(1), ":0,1,0");  // cut short
  (void)g;
}

TEST(NanoScanSim, RStopsARunningPassAtOnce) {
  auto rig = bootedRig();
  Events ev = {{0, 15}, {500000, 0}};
  ASSERT_EQ(load(*rig, programs(ev)[0]), "K:0");
  uint64_t g = start(*rig);
  rig->runUs(uv::kProgramStartLeadUs + 1000);
  for (int k = 0; k < 4; k++) ASSERT_TRUE(rig->level('B', 2 + k));
  rig->lineEnds.clear();
  rig->send("R\n");
  rig->runUntil([&] { return !rig->lineEnds.empty(); }, 1000);
  uint64_t rEnd = rig->lineEnds.front();
  rig->runUs(100);
  for (int k = 0; k < 4; k++) {
    ASSERT_FALSE(rig->level('B', 2 + k));
    EXPECT_LT(us(rig->edges('B', 2 + k).back().cycle - rEnd), 50.0);
  }
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,3");
  rig->runUs(600000);  // nothing of the cut pass comes back
  for (int k = 0; k < 4; k++) EXPECT_FALSE(rig->level('B', 2 + k));
  (void)g;
}

TEST(NanoScanSim, ALateOrRepeatedGDoesNothing) {
  auto rig = bootedRig();
  EXPECT_EQ(reply(*rig, "G"), "");  // nothing armed: no reply, nothing lights
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,6");
  ASSERT_EQ(load(*rig, programs({{0, 1}, {100, 0}})[0]), "K:0");
  rig->clearEdges();
  rig->send("G\nG\n");
  rig->runUs(5000);
  EXPECT_EQ(pulses(rig->edges('B', 2)).size(), 1u);  // the second G found nothing armed
}

TEST(NanoScanSim, AChainWhoseMegaFallsSilentIsCut) {
  auto rig = bootedRig();
  Events ev = {{0, 15}, {400000, 0}};
  ASSERT_EQ(load(*rig, programs(ev)[0]), "K:0");
  rig->clearEdges();
  start(*rig);
  rig->runUntil([&] { return rig->lineEnds.size() > 0; }, 1000);
  uint64_t lastLine = rig->lineEnds.back();  // the G: nothing follows it
  rig->runUs(80000);
  for (int k = 0; k < 4; k++) {
    ASSERT_FALSE(rig->level('B', 2 + k)) << "LED " << k << " still on";
    double cutMs = us(rig->edges('B', 2 + k).back().cycle - lastLine) / 1000;
    EXPECT_GT(cutMs, 50.0);
    EXPECT_LT(cutMs, 53.0) << "cut late";
    budget.silenceCutMs = std::max(budget.silenceCutMs, cutMs);
  }
  EXPECT_EQ(reply(*rig, "Q"), "Q:2,0,7");
  EXPECT_EQ(reply(*rig, "C").substr(1), ":0,1,0");
}

// W: the Mega measures the Nano's clock by the micros() at which each W's newline arrived. Over any
// span the answers agree with the simulated time between the newlines within 12 µs (micros() ticks
// 4 µs; the receive interrupt can be held up by another).
TEST(NanoScanSim, WAnswersWhenItsNewlineArrivedByTheNanosOwnClock) {
  auto rig = bootedRig();
  std::vector<std::pair<uint64_t, uint32_t>> seen;  // the newline's cycle, the answer
  for (int i = 0; i < 4; i++) {
    rig->lineEnds.clear();
    const std::string r = reply(*rig, "W");
    ASSERT_EQ(r.rfind("W:", 0), 0u) << r;
    ASSERT_EQ(rig->lineEnds.size(), 1u);
    seen.push_back({rig->lineEnds.front(), static_cast<uint32_t>(std::stoul(r.substr(2)))});
    rig->runUs(150000 + 230000 * i);
  }
  for (size_t i = 1; i < seen.size(); i++) {
    const double byCycles = us(seen[i].first - seen[0].first), byAnswers = seen[i].second - seen[0].second;
    EXPECT_NEAR(byAnswers, byCycles, 12.0) << "W " << i;
  }
}

// Two events closer than the Nano needs from one edge to the next (it reads the next event from the
// store between them): the second comes late by the difference, never early, and nothing else moves.
TEST(NanoScanSim, EventsCloserThanTheNanoTakesBetweenEdgesComeLateNeverEarly) {
  for (uint32_t gap : {4u, 8u, 14u, 20u, 30u, 60u}) {
    auto rig = bootedRig();
    // LED 0 on at 500 µs, LED 1 on `gap` µs later, both off 1000 µs later, LED 2 on for 50 µs after.
    Events ev = {{500, 1}, {500 + gap, 3}, {1500, 0}, {2000, 4}, {2050, 0}};
    auto chain = programs(ev);
    ASSERT_EQ(chain.size(), 1u);
    ASSERT_EQ(load(*rig, chain[0]), "K:0");
    rig->clearEdges();
    const uint64_t g = start(*rig);
    rig->runUs(uv::kProgramStartLeadUs + 3000);
    const double time0 = us(g) + uv::kProgramStartLeadUs;
    auto e0 = rig->edges('B', 2), e1 = rig->edges('B', 3), e2 = rig->edges('B', 4);
    ASSERT_EQ(e0.size(), 2u);
    ASSERT_EQ(e1.size(), 2u);
    ASSERT_EQ(e2.size(), 2u);
    const double base = us(e0[0].cycle) - (time0 + 500);  // time 0's own offset, from the first edge
    const double late = us(e1[0].cycle) - (time0 + 500 + gap) - base;
    EXPECT_GE(late, -1.0) << gap << " us apart: early";
    EXPECT_LE(late, 25.0) << gap << " us apart";
    EXPECT_NEAR(us(e2[0].cycle) - (time0 + 2000) - base, 0, 1.0) << "an event after them moved";
    budget.closeLate.push_back({gap, late});
  }
}
