// A mixed job streamed to the machine (M828, issue 28): dense passes exposed on the move, sparse ones
// stop by stop, in one job; the whole Mega with the real Nano logic, each cell's dose and each LED
// edge measured against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "grid_cells.h"
#include "job_plan.h"
#include "machine_scan_fixture.h"
#include "scan.h"

using namespace mega;
using namespace jobs;

namespace {
struct MixedStreamTest : ScanMachineTest {
  void mixedJob(uint16_t cols, uint16_t rows, uint32_t fullUs) {
    job(cols, rows, fullUs);
    h.strategy = uv::Strategy::Mixed;
    g = scandose::mixedPattern(cols, rows);
  }
  // The way each pass of the job goes, as the planner plans it for this machine: 's' on the move, 'x'
  // stops; and the window of the scan pass that exposes each row (the link cap may slow a pass).
  std::vector<double> windowOfRow;
  std::string ways(uint32_t& steps) {
    windowOfRow.assign(h.rows, 0);
    steps = 0;
    uvtest::GridCells cells(g);
    const uv::Machine machine = plannerMachine(m.config, 0, 0);
    uv::ScanPlanner planner(h, cells, machine);
    std::string out;
    uv::ScanPass p;
    while (planner.nextPass(p)) {
      out += p.stops ? 'x' : 's';
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
    scandose::addSteps(track, m.rig.steps);
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, lights, track, spm, windowOfRow);
  }
};
}  // namespace

TEST_F(MixedStreamTest, AStreamedMixedJobScansTheDensePassesAndStopsForThePadsEveryCellItsDoseInPlace) {
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

// A card job cannot run mixed yet: M29 refuses it before any light with the scan-mode error.
TEST_F(MixedStreamTest, AMixedJobOnTheCardIsRefusedAtM29WithE29) {
  mixedJob(20, 8, 1000);
  const Lines got = upload("MIX.UVJ", encode(h, g));
  m.run(2000000);
  std::string all = ::testing::PrintToString(got) + ::testing::PrintToString(m.usbLines);
  EXPECT_NE(all.find("E29"), std::string::npos) << all;
  EXPECT_FALSE(m.sd.exists("MIX.UVJ~s") && m.cmd("M23 MIX.UVJ").empty());
  EXPECT_EQ(m.nano.fired, 0u);
}
