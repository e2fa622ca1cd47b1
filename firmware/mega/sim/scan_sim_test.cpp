// Exposure on the move on the real images (issue 19): the Mega image plans a streamed scan job pass
// by pass, loads the Nano image's programs, and its step interrupt sends each G on its marked step;
// the rig logs the head's steps and the Nano's LED pins, and every cell's dose and every LED edge
// is measured from them against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <regex>

#include "board_fixture.h"
#include "job_fixture.h"
#include "scan_dose.h"

using namespace mega::jobs;

namespace {

// Streams a scan job to the Mega image, runs it to its end, and measures the light the Nano image
// gave against the head's steps. `passes`: how many the job has.
class ScanOnBoard : public BoardTest {
 protected:
  // A scan job of the grid's size at `fullUs` a full cell, every LED at the same gain.
  static uv::JobHeader scanJob(const Grid& g, uint32_t fullUs) {
    uv::JobHeader h = header(static_cast<uint16_t>(g[0].size()), static_cast<uint16_t>(g.size()), uv::Strategy::Scan);
    h.fullUs = fullUs;
    for (int k = 0; k < 4; k++) h.gainPermille[k] = 1000;
    return h;
  }
  // Both host ports poll the temperatures and the job while it runs (the stack's heaviest run).
  bool pollBothHosts = false;
  int espHeard = 0;  // the ESP port's temperature reports
  scandose::Figures expose(const uv::JobHeader& h, const Grid& g, int passes) {
    EXPECT_TRUE(said(cmd("G28", 8e6), "ok"));
    const int32_t home[2] = {sim.pos[0], sim.pos[1]};  // the Mega's 0 in the rig's count
    sim.logging = true;
    EXPECT_TRUE(said(numbered("M828"), "ok"));
    for (const std::string& r : encode(h, g)) EXPECT_TRUE(said(numbered(r), "ok")) << r;
    EXPECT_TRUE(said(numbered("M29"), "ok"));
    std::string end;
    bool reset = passes < 2;
    uint64_t nextPoll = sim.megaCycle();
    EXPECT_TRUE(sim.runUntil([&] {
      if (pollBothHosts && sim.megaCycle() >= nextPoll) {
        // Both hosts ask what a dashboard asks, every 100 ms, each within its window (mega.md §3).
        sim.send("M105\nM114\nM27\n");
        sim.sendEsp("M105\nM27\n");
        nextPoll = sim.megaCycle() + static_cast<uint64_t>(100e3 * BoardSim::kCyclesPerUs);
      }
      for (std::string& l : sim.takeEspLines()) espHeard += l.rfind("T:", 0) == 0;
      if (!reset && std::count(sim.nanoLines.begin(), sim.nanoLines.end(), "G") == 2) {
        sim.send("M821 R\n");  // the main loop's longest pass, from the second pass's G on
        reset = true;
      }
      for (std::string& l : sim.takeLines()) {
        seen.push_back(l);
        if (l.rfind("JOB:done", 0) == 0 || l.rfind("JOB:failed", 0) == 0 || l.rfind("JOB:paused", 0) == 0) end = l;
      }
      return !end.empty();
    }, 20e6));
    sim.logging = false;
    std::string replies;
    for (const std::string& l : sim.nanoReplies) replies += l + " ";
    EXPECT_EQ(end.rfind("JOB:done", 0), 0u) << end << "\nthe Nano said: " << replies;
    const std::string all = std::to_string(passes);
    EXPECT_NE(end.find("stop=" + all + "/" + all), std::string::npos) << end;
    int gs = 0;
    for (const std::string& l : sim.nanoLines) gs += l == "G";
    EXPECT_EQ(gs, passes);

    scandose::Track track;
    track.add(0, 0, 0);
    for (const BoardSim::HeadStep& s : sim.headSteps) track.add(s.cycle / BoardSim::kCyclesPerUs, s.x - home[0], s.y - home[1]);
    // simavr sends a UART frame in 11 bit-times where the chip takes 10 (93.5 µs against 85.0 at the
    // Mega's divisor, ../shared/TOOLCHAIN.md): the G and its newline reach the simulated Nano 2
    // bit-times (17 µs) later than on the machine, and every edge of the chain with them. The light
    // is measured as the chip would give it.
    constexpr double kSimUartLagUs = 2 * 8.5;
    std::vector<scandose::Light> lights;
    double onAt[4] = {};
    for (const BoardSim::LedEdge& e : sim.ledEdges) {
      const double t = e.cycle / BoardSim::kCyclesPerUs - kSimUartLagUs;
      if (e.on) onAt[e.led] = t;
      else lights.push_back({static_cast<uint8_t>(e.led), onAt[e.led], t});
    }
    EXPECT_FALSE(lights.empty());
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, lights, track, spm, h.fullUs);
  }
  // M821's longest main-loop pass (µs) since the second pass's G (the pass that follows flying, and
  // not the opening of the next, 18 ms at rest), and the step underruns.
  void diagnostics(unsigned& loopMaxUs, unsigned& underruns) {
    std::string line;
    for (const std::string& l : cmd("M821"))
      if (l.rfind("echo:DIAG", 0) == 0) line = l;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(loop_max_us=(\d+) step_isr_max_us=\d+ underruns=(\d+))"))) << line;
    loopMaxUs = std::stoul(m[1]);
    underruns = std::stoul(m[2]);
  }
  // The head's fastest X step, in steps/s.
  double fastestX() const {
    double best = 0;
    for (size_t i = 1; i < sim.headSteps.size(); i++)
      if (sim.headSteps[i].x != sim.headSteps[i - 1].x)
        best = std::max(best, BoardSim::kCyclesPerUs * 1e6 / static_cast<double>(sim.headSteps[i].cycle - sim.headSteps[i - 1].cycle));
    return best;
  }
};

// The Nano's clock's clock against the Mega's, set before both boot: each board's 16 MHz comes from its own
// crystal or resonator, and a resonator is good to 0.5 %. The Mega measures the Nano's clock by W
// (nano_clock.h) and times every event on it; without that, a Nano 0.5 % off put 20 % of a cell's
// dose into its neighbour by the end of these 40 ms passes.
class ScanBoardTest : public ScanOnBoard, public ::testing::WithParamInterface<double> {
 protected:
  void SetUp() override {
    sim.nanoClock = GetParam();
    BoardTest::SetUp();
  }
};

// A Nano 0.3 % fast, so the stretches flown are timed on a clock that is not the Mega's as well.
class ScanFlyingBoardTest : public ScanOnBoard {
 protected:
  void SetUp() override {
    sim.nanoClock = 1.003;
    BoardTest::SetUp();
  }
};
}  // namespace

INSTANTIATE_TEST_SUITE_P(NanoClocks, ScanBoardTest, ::testing::Values(1.0, 1.005, 0.995));

TEST_P(ScanBoardTest, AScanJobOnTheRealImagesGivesEveryCellItsDoseInPlace) {
  // 1-cell lines, runs of full cells and gray steps, at 100 µm and 1 ms a cell: 100 mm/s, the
  // axis's top speed, so no blank stretch is flown.
  const Grid g = scandose::testPattern(40, 10);
  const uv::JobHeader h = scanJob(g, 1000);
  const scandose::Figures f = expose(h, g, 3);  // 10 rows, 4 LEDs a row apart: 3 passes
  std::printf("[scan simavr] real Mega + Nano images, the Nano's clock %+.1f %%, %d cells (%d lit) in 3 passes: worst dose error %.2f %% of the full dose, "
              "worst LED edge %.2f um from its place, worst cell centroid %.2f um (cell 100 um; goals 2 %% and 25 um)\n",
              (GetParam() - 1) * 100, f.cells, f.lit, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm);
  EXPECT_EQ(f.stray, 0);
  // The goal. Measured 1.02 %, and 0.55 % and 0.95 % with the Nano's clock 0.5 % fast and slow
  // (2.27 % before the Nano's timer read its next event inline and the step interrupt held the head
  // back for a late G). It moves by about half a percent with unrelated changes to the images (0.55
  // to 1.60 % seen): each pass's light runs 4 to 11 µs behind the head, by how late the Nano's
  // receive interrupt noted the G's newline, and of two events a few µs apart the second comes up
  // to 5 µs late (the Nano needs about 9 µs from one edge to the next: nano_sim_tests "Closer").
  // Those µs weigh four times less in the flying test's 4 ms cells (0.14 to 0.29 % there).
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// Islands of lit cells far apart at 4 ms a 100 µm cell, 25 mm/s: the Mega flies the stretches
// between them (Motion::StrokeJump), up to the axis's 100 mm/s, and is back at the pass's speed on
// the step and the tick the Nano's program expects.
TEST_F(ScanFlyingBoardTest, FlownStretchesKeepEveryCellItsDoseInPlace) {
  const Grid g = scandose::gapPattern(150, 8);
  const uv::JobHeader h = scanJob(g, 4000);
  pollBothHosts = true;  // and the panel redraws: the heaviest run these images can have (no card here)
  const scandose::Figures f = expose(h, g, 2);
  EXPECT_GT(espHeard, 3);
  const double fastest = fastestX();
  unsigned loopMaxUs = 0, underruns = 1;
  diagnostics(loopMaxUs, underruns);
  std::printf("[scan simavr, flying] real Mega + Nano images, the Nano's clock +0.3 %%, %d cells (%d lit) in 2 passes, the head up to %.0f mm/s "
              "(the passes' speed 25): worst dose error %.2f %% of the full dose, worst LED edge %.2f um from its place, worst cell centroid %.2f um; "
              "longest main-loop pass while the last pass ran %u us (the queued segments cover 40000 us)\n",
              f.cells, f.lit, fastest / 80, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm, loopMaxUs);
  EXPECT_GT(fastest / 80, 50.0);  // it flew
  EXPECT_EQ(underruns, 0u);  // cutting the stretches into segments kept ahead of the step interrupt
  EXPECT_LT(loopMaxUs, 20000u);  // half of what the queue covers
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}
