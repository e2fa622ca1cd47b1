// Exposure on the move on the real images (issue 19): the Mega image plans a streamed scan job pass
// by pass, loads the Nano image's programs, and its step interrupt sends each G on its marked step;
// the rig logs the head's steps and the Nano's LED pins, and every cell's dose and every LED edge
// is measured from them against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "board_fixture.h"
#include "job_fixture.h"
#include "scan_dose.h"

using namespace mega::jobs;

namespace {
// The Nano's clock against the Mega's, set before both boot: each board's 16 MHz comes from its own
// crystal or resonator, and a resonator is good to 0.5 %. The Mega measures the Nano's clock by W
// (nano_clock.h) and times every event on it; without that, a Nano 0.5 % off put 20 % of a cell's
// dose into its neighbour by the end of these 40 ms passes.
class ScanBoardTest : public BoardTest, public ::testing::WithParamInterface<double> {
 protected:
  void SetUp() override {
    sim.nanoClock = GetParam();
    BoardTest::SetUp();
  }
};
}  // namespace

INSTANTIATE_TEST_SUITE_P(NanoClocks, ScanBoardTest, ::testing::Values(1.0, 1.005, 0.995));

TEST_P(ScanBoardTest, AScanJobOnTheRealImagesGivesEveryCellItsDoseInPlace) {
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  const int32_t home[2] = {sim.pos[0], sim.pos[1]};  // the Mega's 0 in the rig's count
  // 1-cell lines, runs of full cells and gray steps, at 100 µm and 1 ms a cell: 100 mm/s, the
  // axis's top speed, so no blank stretch is flown.
  const uint16_t cols = 40, rows = 10;
  const Grid g = scandose::testPattern(cols, rows);
  uv::JobHeader h = header(cols, rows, uv::Strategy::Scan);
  h.fullUs = 1000;
  for (int k = 0; k < 4; k++) h.gainPermille[k] = 1000;
  sim.logging = true;
  ASSERT_TRUE(said(numbered("M828"), "ok"));
  for (const std::string& r : encode(h, g)) ASSERT_TRUE(said(numbered(r), "ok")) << r;
  ASSERT_TRUE(said(numbered("M29"), "ok"));
  std::string end;
  ASSERT_TRUE(sim.runUntil([&] {
    for (std::string& l : sim.takeLines()) {
      seen.push_back(l);
      if (l.rfind("JOB:done", 0) == 0 || l.rfind("JOB:failed", 0) == 0 || l.rfind("JOB:paused", 0) == 0) end = l;
    }
    return !end.empty();
  }, 20e6));
  sim.logging = false;
  std::string replies;
  for (const std::string& l : sim.nanoReplies) replies += l + " ";
  ASSERT_EQ(end.rfind("JOB:done", 0), 0u) << end << "\nthe Nano said: " << replies;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;  // 10 rows, 4 LEDs a row apart: 3 passes
  int gs = 0;
  for (const std::string& l : sim.nanoLines) gs += l == "G";
  EXPECT_EQ(gs, 3);

  scandose::Track track;
  track.add(0, 0, 0);
  for (const BoardSim::HeadStep& s : sim.headSteps) track.add(s.cycle / BoardSim::kCyclesPerUs, s.x - home[0], s.y - home[1]);
  // simavr sends a UART frame in 11 bit-times where the chip takes 10 (93.5 µs against 85.0 at the
  // Mega's divisor, ../shared/TOOLCHAIN.md): the G and its newline reach the simulated Nano 2 bit-times
  // (17 µs) later than on the machine, and every edge of the chain with them. The light is measured
  // as the chip would give it.
  constexpr double kSimUartLagUs = 2 * 8.5;
  std::vector<scandose::Light> lights;
  double onAt[4] = {};
  for (const BoardSim::LedEdge& e : sim.ledEdges) {
    const double t = e.cycle / BoardSim::kCyclesPerUs - kSimUartLagUs;
    if (e.on) onAt[e.led] = t;
    else lights.push_back({static_cast<uint8_t>(e.led), onAt[e.led], t});
  }
  ASSERT_FALSE(lights.empty());
  const double spm[2] = {80, 80};
  const scandose::Figures f = scandose::measure(h, g, lights, track, spm, 1000);
  std::printf("[scan simavr] real Mega + Nano images, the Nano's clock %+.1f %%, %d cells (%d lit) in 3 passes: worst dose error %.2f %% of the full dose, "
              "worst LED edge %.2f um from its place, worst cell centroid %.2f um (cell 100 um; goals 2 %% and 25 um)\n",
              (GetParam() - 1) * 100, f.cells, f.lit, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm);
  EXPECT_EQ(f.stray, 0);
  // The goal. Measured 0.68 %, and 0.55 % and 0.80 % with the Nano's clock 0.5 % fast and slow
  // (2.27 % before the Nano's timer read its next event inline and the step interrupt held the head
  // back for a late G). It moves by about half a percent with unrelated changes to the images (0.55
  // to 1.55 % seen): each pass's light runs 4 to 11 µs behind the head, by how late the Nano's
  // receive interrupt noted the G's newline, and of two events a few µs apart the second comes up
  // to 5 µs late (the Nano needs about 9 µs from one edge to the next: nano_sim_tests "Closer").
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}
