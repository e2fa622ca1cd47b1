// A scan job streamed to the machine (M828) and exposed on the move: the whole Mega (host link,
// stream, job runner, ScanRun, motion) with the real Nano logic, each cell's dose and each LED edge
// measured against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
struct ScanStreamTest : ScanMachineTest {
  void exposeWithTheNanosClockOff(int32_t ppm);
};
}  // namespace

TEST_F(ScanStreamTest, AScanJobSlowerThanTheTopSpeedFliesItsBlankStretches) {
  job(60, 8, 2000);  // 2 ms a 100 µm cell: 50 mm/s, half the top speed
  for (auto& row : g) {
    row.assign(60, 0);
    for (uint16_t c : {2, 3, 4, 20, 41, 42, 59}) row[c] = static_cast<uint8_t>(c == 20 ? 128 : 255);  // pads far apart
  }
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  const scandose::Figures f = measure(2000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=2/2"), std::string::npos) << end;
  // The stretches between the pads are flown: some X steps come faster than 50 mm/s allows.
  const uint64_t shortest = shortestXStep(m.rig.steps);
  std::printf("[scan machine] blank stretches flown, at up to %.0f mm/s in 50 mm/s passes: worst dose error %.2f %% of full, worst edge %.2f um (cell 100 um)\n",
              2e6 / shortest / 80, f.worstDosePct, f.worstEdgeUm);
  EXPECT_LT(shortest, 2000000u / 4000 * 3 / 4);  // 4000 steps/s is 50 mm/s at 80 steps/mm
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
}

TEST_F(ScanStreamTest, AStreamedScanJobIsExposedOnTheMoveEveryCellItsDoseInPlace) {
  job(40, 10, 1000);  // 1 ms a 100 µm cell: 100 mm/s, the axis's top speed
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  const scandose::Figures f = measure(1000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;  // 10 rows, 4 LEDs: 3 passes
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_TRUE(m.nano.exposures.empty());  // no F: all of it came from the chains
  std::printf("[scan machine] %d cells (%d lit): worst dose error %.2f %% of full, worst centroid %.2f um, worst edge %.2f um (cell 100 um)\n",
              f.cells, f.lit, f.worstDosePct, f.worstCentreUm, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// Each board has its own crystal or resonator: here the Nano's clock runs 0.5 % off, a resonator's
// tolerance. The Mega measures it by W before the first pass and times every event on it; without
// that, the 40 ms passes would shift by 200 µs by their ends, a fifth of a cell.
void ScanStreamTest::exposeWithTheNanosClockOff(int32_t ppm) {
  m.nano.clockPpm = ppm;
  // The fake's micros() runs at clockPpm since its start, so a W answered before this line read a
  // clock that now seems to jump: the Mega's measurement starts again after it (a Nano silent long
  // enough to be given up), and W measures the rate alone.
  m.nano.silent = true;
  m.run(300000);
  m.nano.silent = false;
  job(40, 10, 1000);
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  const int32_t measured = m.head.nanoClock().ppm();
  EXPECT_NEAR(measured, ppm, 5);
  const scandose::Figures f = measure(1000);
  std::printf("[scan machine] the Nano's clock %+d ppm, measured %+d: worst dose error %.2f %% of full, worst edge %.2f um\n", ppm, measured,
              f.worstDosePct, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
}

TEST_F(ScanStreamTest, ANanoClockFastByAResonatorsToleranceStillGivesEveryCellItsDose) { exposeWithTheNanosClockOff(5000); }
TEST_F(ScanStreamTest, ANanoClockSlowByAResonatorsToleranceStillGivesEveryCellItsDose) { exposeWithTheNanosClockOff(-5000); }

// A Nano whose firmware predates W: its clock cannot be measured, so no pass runs. The job ends
// with E29 after the wait, with no light, rather than waiting for ever.
TEST_F(ScanStreamTest, ANanoThatNeverAnswersWEndsTheScanJobWithE29AndNoLight) {
  m.nano.noClock = true;
  job(40, 10, 1000);
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 30000000);
  EXPECT_EQ(end.rfind("JOB:failed", 0), 0u) << end;
  EXPECT_TRUE(has(m.usbLines, "FAULT:E29 scan job not supported by this machine at stop 0")) << ::testing::PrintToString(m.usbLines);
  EXPECT_TRUE(m.nano.scanLight.empty());
  EXPECT_TRUE(m.head.online());  // the polls it does answer keep it online
}

TEST_F(ScanStreamTest, M524MidPassSwitchesTheLedsOffAndStopsTheHead) {
  job(90, 4, 1000);  // one pass of 90 ms (the 512-byte stream buffer holds its 4 rows)
  stream();
  ASSERT_TRUE(lightOn());
  m.cmd("M524");
  m.run(1000);
  EXPECT_EQ(m.nano.lit(), 0);
  m.run(300000);
  EXPECT_TRUE(has(m.usbLines, "JOB:aborted"));
  EXPECT_TRUE(m.rig.motion.idle());
  const size_t lights = m.nano.scanLight.size();
  m.run(1000000);
  EXPECT_EQ(m.nano.scanLight.size(), lights);  // nothing more lit
  EXPECT_TRUE(has(payload("M114"), "X:"));     // and the machine takes commands again
}

TEST_F(ScanStreamTest, M25PausesBetweenPassesAndM24GoesOnWithTheNext) {
  job(40, 10, 1000);
  stream();
  ASSERT_TRUE(lightOn());  // in the first pass
  m.cmd("M25");
  const std::string paused = runUntilJob({"paused", "done", "failed"}, 20000000);
  ASSERT_NE(paused.find("JOB:paused"), std::string::npos) << paused;
  EXPECT_NE(paused.find("stop=1/"), std::string::npos) << paused;  // the pass under way ran whole first
  EXPECT_EQ(m.nano.lit(), 0);
  const size_t lights = m.nano.scanLight.size();
  m.run(500000);
  EXPECT_EQ(m.nano.scanLight.size(), lights);
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;
}

// Whatever planned it, a pass whose stroke would leave the bed (here its run-out, past the artwork's
// right edge on the bed's) fails with E15 before the head sets off, and nothing is lit.
TEST_F(ScanStreamTest, AStrokeThatWouldLeaveTheBedFailsWithE15BeforeTheHeadSetsOff) {
  job(40, 10, 1000);
  h.originUm[0] = 200000 - 40 * 100;  // the last column ends at X 200 mm, the bed's edge
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  EXPECT_TRUE(has(m.usbLines, "FAULT:E15 target outside soft limits at stop 0")) << end;
  EXPECT_TRUE(has(m.usbLines, "JOB:failed")) << end;  // then aborted, as a stream that fails is
  EXPECT_LE(m.rig.head[0], 200 * 80);  // steps: never past the bed's 200 mm
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_TRUE(m.nano.scanLight.empty());
}
