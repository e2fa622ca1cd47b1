// A mixed job on the machine (issue 28), streamed (M828) and from the card: dense passes exposed on
// the move, sparse ones stop by stop or as a band of stops, in one job; the whole Mega with the real Nano logic, each
// cell's dose and each LED edge measured against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "grid_cells.h"
#include "job_plan.h"
#include "machine_scan_fixture.h"
#include "scan.h"

using namespace mega;
using namespace jobs;

namespace {
struct MixedMachineTest : ScanMachineTest {
  void mixedJob(uint16_t cols, uint16_t rows, uint32_t fullUs) {
    job(cols, rows, fullUs);
    h.strategy = uv::Strategy::Mixed;
    g = scandose::mixedPattern(cols, rows);
  }
  // The way each pass of the job goes, as the planner plans it for this machine: 's' on the move, 'x'
  // stops, 'b' a band of stops (planner.md "Bands"); and the window of the scan pass that exposes each
  // row (the link cap may slow a pass); and the stops before the first band of stops.
  std::vector<double> windowOfRow;
  uint32_t stopsBeforeBand = 0;
  std::string ways(uint32_t& steps) {
    windowOfRow.assign(h.rows, 0);
    steps = 0;
    stopsBeforeBand = 0;
    uvtest::GridCells cells(g);
    const uv::MotionModel machine = plannerMachine(m.config, 0, 0, m.head.jobBaud());
    uv::ScanPlanner planner(h, cells, machine);
    std::string out;
    uv::ScanPass p;
    while (planner.nextPass(p)) {
      if (p.band && out.find('b') == std::string::npos) stopsBeforeBand = steps - static_cast<uint32_t>(std::count(out.begin(), out.end(), 's'));
      out += p.band ? 'b' : p.stops ? 'x' : 's';
      steps += p.stops ? 0 : 1;  // a pass on the move counts one, a stop one
      for (int k = 0; k < 4 && !p.stops; k++) {
        const int row = p.hy + h.offsets[k][1];
        if (row >= 0 && row < h.rows) windowOfRow[row] = planner.passMotion().windowUs;
      }
      uv::Stop s;
      while (planner.nextStop(s)) steps++;
      uint32_t t;
      uint8_t mask;
      while (planner.nextEvent(t, mask)) {
      }
    }
    return out;
  }
  // The light of the Nano's chains and of its F exposures together.
  scandose::Figures measureAll() {
    std::vector<scandose::Light> lights = scandose::lightsOf(m.nano.scanLight);
    for (const auto& e : m.nano.exposures)
      for (uint8_t k = 0; k < 4; k++)
        if (e.litUs[k]) lights.push_back({k, static_cast<double>(e.startUs), static_cast<double>(e.startUs + e.litUs[k])});
    scandose::Track track;
    track.add(0, 0, 0);
    scandose::addSteps(track, before);
    scandose::addSteps(track, m.rig.steps);
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, lights, track, spm, windowOfRow);
  }
};
}  // namespace

TEST_F(MixedMachineTest, AStreamedMixedJobScansTheDensePassesAndStopsForThePadsEveryCellItsDoseInPlace) {
  mixedJob(40, 16, 1000);  // 1 ms a 100 µm cell: 100 mm/s, the axis's top speed
  uint32_t steps = 0;
  const std::string plan = ways(steps);
  ASSERT_EQ(plan, "sxsx");  // 16 rows, 4 LEDs: 4 passes, the dense ones on the move
  m.nano.logging = true;
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  const scandose::Figures f = measureAll();
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  const std::string count = std::to_string(steps);
  EXPECT_NE(end.find("stop=" + count + "/" + count), std::string::npos) << end;  // a pass on the move is one, a stop one
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_EQ(m.nano.exposures.size(), steps - 2);  // the pads' stops by F, the rest in the two chains
  EXPECT_FALSE(m.nano.scanLight.empty());
  std::printf("[mixed machine] passes %s ('s' on the move, 'x' stops), %d cells (%d lit): worst dose error %.2f %% of full, worst centroid %.2f um, worst edge %.2f um (cell 100 um)\n",
              plan.c_str(), f.cells, f.lit, f.worstDosePct, f.worstCentreUm, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

TEST_F(MixedMachineTest, AMixedJobOnTheCardRunsStepByStepEveryCellItsDoseInPlace) {
  mixedJob(40, 16, 1000);
  uint32_t steps = 0;
  ASSERT_EQ(ways(steps), "sxsx");
  ASSERT_TRUE(has(upload("MIX.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 MIX.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();  // the track starts at the origin
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  const std::string count = std::to_string(steps);
  EXPECT_NE(end.find("stop=" + count + "/" + count), std::string::npos) << end;  // counted at M29 as it runs
  EXPECT_EQ(m.nano.exposures.size(), steps - 2);
  const scandose::Figures f = measureAll();
  std::printf("[mixed card] passes sxsx from the card: worst dose error %.2f %% of full, worst edge %.2f um (cell 100 um)\n", f.worstDosePct, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
}

// A reset between two stops of a stop pass: the job resumes from its checkpoint, the card's planner
// passes over the steps done (the first pass on the move and the first stop) and takes up the stop
// pass where it was; every cell gets its dose, and none twice but the stop the reset may have cut.
TEST_F(MixedMachineTest, AResetInAStopPassResumesAtTheStopThatWasNext) {
  mixedJob(40, 16, 1000);
  uint32_t steps = 0;
  ASSERT_EQ(ways(steps), "sxsx");
  const std::string count = std::to_string(steps);
  ASSERT_TRUE(has(upload("R.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 R.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M24");
  // Until the first stop's light is out: the pass on the move and that stop done.
  for (int i = 0; i < 200000 && (m.nano.exposures.empty() || m.nano.lit()); i++) m.run(100);
  ASSERT_EQ(m.nano.exposures.size(), 1u);
  m.run(5000);
  before = m.rig.steps;
  m.reset(200000);
  EXPECT_EQ(m.nano.lit(), 0);
  const std::string interrupted = payload("M1000 S")[0];
  ASSERT_EQ(interrupted.rfind("JOB:interrupted file=R.UVJ stop=", 0), 0u) << interrupted;
  EXPECT_TRUE(interrupted.find("stop=1/" + count) != std::string::npos || interrupted.find("stop=2/" + count) != std::string::npos) << interrupted;
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M1000");
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=" + count + "/" + count), std::string::npos) << end;
  const scandose::Figures f = measureAll();
  const uv::Durations dose(h);
  const double full = dose.us(0, 255);
  int over = 0;
  for (uint16_t r = 0; r < h.rows; r++)
    for (uint16_t c = 0; c < h.cols; c++) {
      const double want = dose.us(0, g[r][c]), got = f.dose[r][c];
      ASSERT_GE(got, want - 0.02 * full) << "cell " << r << "," << c;
      over += got > want + 0.02 * full;
    }
  std::printf("[mixed card] a reset after the first stop of the stop pass: %d cells more than their dose, all others once\n", over);
  EXPECT_LE(over, 1);  // at most the stop under way when the reset came
}

// A band of stops (planner.md "Bands") streamed: the first band of 8 passes goes pass by pass, the
// next, a cell at one end or the other of every other row, as one band of stops column by column;
// every cell its dose.
TEST_F(MixedMachineTest, AStreamedMixedJobTakesASparseBandAsOneBandOfStops) {
  job(40, 48, 1000);
  h.strategy = uv::Strategy::Mixed;
  g = scandose::bandedPattern(40, 48, 16);
  uint32_t steps = 0;
  const std::string plan = ways(steps);
  ASSERT_EQ(plan, "sxsxxxxxb");
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  const std::string count = std::to_string(steps);
  EXPECT_NE(end.find("stop=" + count + "/" + count), std::string::npos) << end;
  EXPECT_EQ(m.nano.exposures.size(), steps - 2);  // every stop by F, the band's too
  const scandose::Figures f = measureAll();
  std::printf("[mixed machine] passes %s ('b' a band of stops), streamed: worst dose error %.2f %% of full, worst edge %.2f um (cell 100 um)\n",
              plan.c_str(), f.worstDosePct, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
}

// A reset between two stops of a band of stops on the card: the card's planner passes over the steps
// done, the band's first stops among them, and takes the band up at the stop that was next.
TEST_F(MixedMachineTest, AResetInABandOfStopsResumesAtTheStopThatWasNext) {
  job(40, 48, 1000);
  h.strategy = uv::Strategy::Mixed;
  g = scandose::bandedPattern(40, 48, 16);
  uint32_t steps = 0;
  ASSERT_EQ(ways(steps), "sxsxxxxxb");
  const std::string count = std::to_string(steps);
  ASSERT_TRUE(has(upload("B.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 B.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M24");
  // Until the band's third stop's light is out.
  const size_t fired = stopsBeforeBand + 3;
  for (int i = 0; i < 400000 && (m.nano.exposures.size() < fired || m.nano.lit()); i++) m.run(100);
  ASSERT_EQ(m.nano.exposures.size(), fired);
  m.run(5000);
  before = m.rig.steps;
  m.reset(200000);
  EXPECT_EQ(m.nano.lit(), 0);
  const std::string interrupted = payload("M1000 S")[0];
  ASSERT_EQ(interrupted.rfind("JOB:interrupted file=B.UVJ stop=", 0), 0u) << interrupted;
  const uint32_t done = static_cast<uint32_t>(fired) + 2;  // the stops, and the two passes on the move
  EXPECT_TRUE(interrupted.find("stop=" + std::to_string(done - 1) + "/" + count) != std::string::npos ||
              interrupted.find("stop=" + std::to_string(done) + "/" + count) != std::string::npos)
      << interrupted;
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M1000");
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=" + count + "/" + count), std::string::npos) << end;
  const scandose::Figures f = measureAll();
  const uv::Durations dose(h);
  const double full = dose.us(0, 255);
  int over = 0;
  for (uint16_t r = 0; r < h.rows; r++)
    for (uint16_t c = 0; c < h.cols; c++) {
      const double want = dose.us(0, g[r][c]), got = f.dose[r][c];
      ASSERT_GE(got, want - 0.02 * full) << "cell " << r << "," << c;
      over += got > want + 0.02 * full;
    }
  std::printf("[mixed card] a reset after the band of stops' third stop: %d cells more than their dose, all others once\n", over);
  EXPECT_LE(over, 1);  // at most the stop under way when the reset came
}
