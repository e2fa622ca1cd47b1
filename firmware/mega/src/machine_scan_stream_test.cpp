// A scan job streamed to the machine (M828) and exposed on the move: the whole Mega (host link,
// stream, job runner, ScanRun, motion) with the real Nano logic, each cell's dose and each LED edge
// measured against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "machine_job_fixture.h"
#include "scan_dose.h"

using namespace mega;
using namespace jobs;

namespace {

// 1-cell lines, runs and gray steps; every LED at the same gain, so a cell's dose is its value's.
Grid scanPattern(uint16_t cols, uint16_t rows) {
  Grid g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c = 0; c < cols; c++) {
      if (r % 3 == 0) g[r][c] = (c % 2) ? 255 : 0;
      else if (r % 3 == 1) g[r][c] = (c / 4) % 2 ? 255 : 0;
      else g[r][c] = static_cast<uint8_t>((c * 41 + r * 13) % 256);
    }
  return g;
}

uv::JobHeader scanHeader(uint16_t cols, uint16_t rows, uint32_t fullUs) {
  uv::JobHeader h = header(cols, rows, uv::Strategy::Scan);
  h.fullUs = fullUs;
  for (int k = 0; k < 4; k++) h.gainPermille[k] = 1000;
  return h;
}

}  // namespace

struct ScanStreamTest : JobTest {
  // Streams the job, runs it to its end; returns the figures of its light.
  scandose::Figures expose(const uv::JobHeader& h, const Grid& g, uint32_t windowUs, std::string& end) {
    m.rig.steps.clear();
    m.cmd("M828");
    for (const std::string& r : encode(h, g)) m.cmd(r);
    m.cmd("M29");
    end = runUntilJob({"done", "failed", "paused", "aborted"}, 120000000);
    scandose::Track track;
    int32_t x = 0, y = 0;
    track.add(0, 0, 0);
    for (const StepEvent& e : m.rig.steps) {
      if (e.axes & 1) x += (e.dirNeg & 1) ? -1 : 1;
      if (e.axes & 2) y += (e.dirNeg & 2) ? -1 : 1;
      track.add(e.us2 / 2.0, x, y);
    }
    std::vector<scandose::Light> lights;
    for (const ScanLight& l : m.nano.scanLight) lights.push_back({l.led, static_cast<double>(l.onUs), static_cast<double>(l.offUs)});
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, lights, track, spm, windowUs);
  }
};

TEST_F(ScanStreamTest, AScanJobSlowerThanTheTopSpeedCrossesItsBlankStretchesAtItsSpeed) {
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  const uint16_t cols = 60, rows = 8;
  Grid g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c : {2, 3, 4, 20, 41, 42, 59}) g[r][c] = static_cast<uint8_t>(c == 20 ? 128 : 255);  // pads far apart
  const uv::JobHeader h = scanHeader(cols, rows, 2000);  // 2 ms a 100 µm cell: 50 mm/s, half the top speed
  std::string end;
  const scandose::Figures f = expose(h, g, 2000, end);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=2/2"), std::string::npos) << end;
  std::printf("[scan machine] blank stretches crossed at 50 mm/s: worst dose error %.2f %% of full, worst edge %.2f um (cell 100 um)\n",
              f.worstDosePct, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
}

TEST_F(ScanStreamTest, AStreamedScanJobIsExposedOnTheMoveEveryCellItsDoseInPlace) {
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  const uint16_t cols = 40, rows = 10;
  const Grid g = scanPattern(cols, rows);
  const uv::JobHeader h = scanHeader(cols, rows, 1000);  // 1 ms a 100 µm cell: 100 mm/s, the axis's top speed
  std::string end;
  const scandose::Figures f = expose(h, g, 1000, end);
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

TEST_F(ScanStreamTest, M524MidPassSwitchesTheLedsOffAndStopsTheHead) {
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  const uint16_t cols = 90, rows = 4;  // one pass of 90 ms (the 512-byte stream buffer holds its 4 rows)
  const uv::JobHeader h = scanHeader(cols, rows, 1000);
  const Grid g = scanPattern(cols, rows);
  m.cmd("M828");
  for (const std::string& r : encode(h, g)) m.cmd(r);
  m.cmd("M29");
  // Until the light is on, then abort.
  for (int i = 0; i < 20000 && m.nano.lit() == 0; i++) m.run(100);
  ASSERT_NE(m.nano.lit(), 0) << ::testing::PrintToString(m.usbLines);
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
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  const uint16_t cols = 40, rows = 10;
  const uv::JobHeader h = scanHeader(cols, rows, 1000);
  const Grid g = scanPattern(cols, rows);
  m.cmd("M828");
  for (const std::string& r : encode(h, g)) m.cmd(r);
  m.cmd("M29");
  for (int i = 0; i < 20000 && m.nano.lit() == 0; i++) m.run(100);
  ASSERT_NE(m.nano.lit(), 0);  // in the first pass
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
