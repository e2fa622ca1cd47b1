// A scan job uploaded to the card (M28/M29, M23, M24): its passes counted and timed at M29, planned
// again pass by pass as they run, each checkpointed, and resumed after a reset with the pass it cut
// exposed again. Every cell's dose measured from the light and the head's steps (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "grid_cells.h"
#include "job_files.h"
#include "job_plan.h"
#include "kept_pass.h"
#include "le_bytes.h"
#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
using ScanCardTest = ScanMachineTest;
}  // namespace

TEST_F(ScanCardTest, AScanJobOnTheCardRunsPassByPassEveryCellItsDose) {
  job(40, 10, 2000);  // 2 ms a 100 µm cell: 50 mm/s, blank stretches crossed at it
  Lines got = upload("SCAN.UVJ", encode(h, g));
  ASSERT_TRUE(has(got, "echo:Done saving file.")) << ::testing::PrintToString(got);
  EXPECT_TRUE(m.sd.exists("SCAN.UVJ~s"));
  m.cmd("M23 SCAN.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();  // the track starts at the origin
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;
  EXPECT_TRUE(m.nano.exposures.empty());
  EXPECT_EQ(payload("M1000 S"), (Lines{"JOB:idle"}));  // the checkpoint is gone with the job done
  const scandose::Figures f = measure(2000);
  std::printf("[scan card] %d cells, 3 passes from the card: worst dose error %.2f %% of full, worst edge %.2f um\n", f.cells, f.worstDosePct,
              f.worstEdgeUm);
  expectEveryCellItsDose(f);
}

TEST_F(ScanCardTest, AResetMidPassResumesWithThatPassExposedAgainAndTheOthersOnce) {
  job(40, 10, 2000);
  for (auto& row : g) std::fill(row.begin() + 10, row.begin() + 30, 0);  // a stretch each pass flies at 50 mm/s
  ASSERT_TRUE(has(upload("R.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 R.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();  // the track starts at the origin; the re-homing after the reset is in it
  m.cmd("M24");
  ASSERT_NE(runUntilJob({"running file=R.UVJ stop=1/3"}, 20000000), "(none)");  // into the second pass
  ASSERT_TRUE(lightOn());
  before = m.rig.steps;
  m.reset(200000);  // the Nano stays powered: the silent Mega cuts its chain after 50 ms
  EXPECT_EQ(m.nano.lit(), 0);
  ASSERT_EQ(payload("M1000 S")[0].rfind("JOB:interrupted file=R.UVJ stop=1/3", 0), 0u);
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M1000");
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_TRUE(has(m.usbLines, "echo:resume: stop 1 was cut short, and is exposed again"));
  // The first and third passes' cells got their dose once; the second's at least once, more
  // where the cut chain had lit them before the reset.
  const scandose::Figures f = measure(2000);
  const uv::Durations dose(h);
  const double full = dose.us(0, 255);
  int over = 0;
  for (uint16_t r = 0; r < h.rows; r++)
    for (uint16_t c = 0; c < h.cols; c++) {
      const double want = dose.us(0, g[r][c]), got = f.dose[r][c];
      ASSERT_GE(got, want - 0.02 * full) << "cell " << r << "," << c;
      const bool secondPass = r >= 4 && r < 8;
      if (!secondPass) {
        ASSERT_LE(got, want + 0.02 * full) << "cell " << r << "," << c << " exposed twice";
      } else if (got > want + 0.02 * full) {
        over++;
      }
    }
  EXPECT_LT(shortestXStep(m.rig.steps), 2000000u / 4000 * 3 / 4);  // the resumed passes flew (4000 steps/s is their 50 mm/s)
  std::printf("[scan card] a reset in pass 2 of 3: %d of its cells lit before the cut got more than their dose; all others once\n", over);
}

TEST_F(ScanCardTest, APassCutForHeatPausesAndContinueExposesItAgain) {
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("H.UVJ", encode(h, g)), "echo:Done saving file."));
  start("H.UVJ");
  ASSERT_NE(runUntilJob({"running file=H.UVJ stop=1/3"}, 20000000), "(none)");
  ASSERT_TRUE(lightOn());
  m.nano.setTemps(900);  // the Nano's own guard cuts the chain
  const std::string paused = runUntilJob({"paused", "done", "failed"}, 5000000);
  ASSERT_NE(paused.find("JOB:paused"), std::string::npos) << paused;
  EXPECT_NE(paused.find("stop=1/3"), std::string::npos) << paused;  // the cut pass is not counted
  EXPECT_EQ(m.nano.lit(), 0);
  m.nano.setTemps(250);
  m.run(2000000);  // cool, and the fault reported
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;
  const scandose::Figures f = measure(2000);
  const uv::Durations dose(h);
  const double full = dose.us(0, 255);
  for (uint16_t r = 0; r < h.rows; r++)
    for (uint16_t c = 0; c < h.cols; c++) {
      const double want = dose.us(0, g[r][c]);
      ASSERT_GE(f.dose[r][c], want - 0.02 * full) << "cell " << r << "," << c;
      if (r < 4 || r >= 8) {
        ASSERT_LE(f.dose[r][c], want + 0.02 * full) << "cell " << r << "," << c << " exposed twice";
      }
    }
}

TEST_F(ScanCardTest, AJobWhosePassWouldOutlastTheStrokesTickCountIsRefusedAtM29BeforeAnyLight) {
  // 5 mm cells at 10 s each, every other one lit: a pass of 240 windows takes 2400 s, over the
  // 2100 s a stroke can count in 0.5 µs ticks (kScanLongestPassUs).
  job(240, 4, 10000000);
  h.pitchUm[0] = h.pitchUm[1] = 5000;
  for (auto& row : g)
    for (uint16_t c = 0; c < h.cols; c++) row[c] = c % 2 ? 255 : 0;
  Lines got = upload("LONG.UVJ", encode(h, g));
  EXPECT_TRUE(has(got, "echo:E29 scan job not supported by this machine")) << ::testing::PrintToString(got);
  m.cmd("G28");
  EXPECT_EQ(payload("M24"), (Lines{"echo:E26 no job selected"}));
  EXPECT_TRUE(m.nano.scanLight.empty());
}

TEST_F(ScanCardTest, AJobWhoseStepTheEngineCannotMakeIsRefusedAtM29BeforeAnyLight) {
  // 200 ms windows at 50 µm and 80 steps/mm: 4 steps a window, 50 ms a step, over the step engine's
  // 32.768 ms. The planner knows it (planner.md "Limits"), so M29 refuses it rather than M24 failing.
  job(12, 4, 200000);
  h.pitchUm[0] = h.pitchUm[1] = 50;
  for (auto& row : g)
    for (uint16_t c = 0; c < h.cols; c++) row[c] = 255;
  Lines got = upload("SLOW.UVJ", encode(h, g));
  EXPECT_TRUE(has(got, "echo:E29 scan job not supported by this machine")) << ::testing::PrintToString(got);
  m.cmd("G28");
  EXPECT_EQ(payload("M24"), (Lines{"echo:E26 no job selected"}));
  EXPECT_TRUE(m.nano.scanLight.empty());
}

TEST_F(ScanCardTest, APhotoWhosePassesWouldOutrunThePrintheadLinkRunsSlowerEveryCellItsDose) {
  // A photo: every cell a different gray, so each LED switches twice a window, 2 ms each: some
  // 13 kB/s of packed program lines (30 in decimal A lines) for a link that carries 11.5. The planner slows each pass until its
  // lines fit (planner.md "The printhead link"), so M29 takes it and every chain runs whole.
  photo(200, 8, 2000);
  Lines got = upload("PHOTO.UVJ", encode(h, g));
  ASSERT_TRUE(has(got, "echo:Done saving file.")) << ::testing::PrintToString(got);
  // Each row's pass window, as the planner lays it out.
  const std::vector<double> windows = scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, m.head.jobBaud()));
  EXPECT_GT(windows[0], 2000 * 1.4);  // slowed to under 72 % of the speed the dose allows
  ASSERT_NO_FATAL_FAILURE(runToDone("PHOTO.UVJ"));
  const scandose::Figures f = measure(windows);
  std::printf("[scan card] a photo slowed for the link (windows %.0f and %.0f us): worst dose error %.2f %% of full, worst edge %.2f um\n",
              windows[0], windows[h.rows - 1], f.worstDosePct, f.worstEdgeUm);
  expectEveryCellItsDose(f);
}

// A card job's passes open as its plan found them at M29, kept in its index file after the rows
// (kept_pass.h), so no pass is laid out or walked for the link again before it runs: what is kept
// is what the planner's own layout and search find, and a pass runs as kept (here the second pass's
// window made half as long again: it runs that much slower, every cell its dose).
TEST_F(ScanCardTest, APhotoOnTheCardOpensEachPassAsItsIndexKeepsIt) {
  photo(200, 8, 2000);
  ASSERT_TRUE(has(upload("KEPT.UVJ", encode(h, g)), "echo:Done saving file."));
  uvtest::GridCells cells(g);
  const uv::MotionModel machine = plannerMachine(m.config, 0, 0, m.head.jobBaud());
  uv::ScanPlanner search(h, cells, machine);  // holds the machine by reference
  std::vector<uint32_t> found;
  std::vector<int32_t> hy;
  std::vector<uv::KeptPass> kept;
  for (uv::ScanPass p; search.nextPass(p);) {
    found.push_back(search.passMotion().windowUs);
    hy.push_back(p.hy);
    kept.emplace_back();
    search.keep(p, kept.back());
  }
  ASSERT_EQ(found.size(), 2u);
  ASSERT_GT(found[1], 2000u);  // capped for the link: a search of more than one walk
  std::string index = m.sd.contents("KEPT.UVJ~i");
  ASSERT_EQ(index.size(), keptPassAt(h.rows, 2));
  for (uint32_t k = 0; k < 2; k++) {
    char b[kKeptPassBytes];
    putKeptPass(kept[k], b);
    EXPECT_EQ(index.substr(keptPassAt(h.rows, k), kKeptPassBytes), std::string(b, sizeof b)) << "pass " << k;
  }
  uv::KeptPass slower = kept[1];
  slower.windowUs = found[1] * 3 / 2;
  putKeptPass(slower, &index[keptPassAt(h.rows, 1)]);
  m.sd.put("KEPT.UVJ~i", index);
  ASSERT_NO_FATAL_FAILURE(runToDone("KEPT.UVJ"));
  std::vector<double> windowOfRow(h.rows, 0);
  for (size_t k = 0; k < 2; k++)
    for (uint8_t led = 0; led < 4; led++) {
      const int32_t r = hy[k] + h.offsets[led][1];
      if (r >= 0 && r < h.rows) windowOfRow[r] = k == 1 ? found[1] * 3 / 2 : found[0];
    }
  const scandose::Figures f = measure(windowOfRow);
  std::printf("[scan card] passes as kept in the index (at %u us, and %u kept for %u): worst dose error %.2f %% of full, worst edge %.2f um\n",
              found[0], found[1] * 3 / 2, found[1], f.worstDosePct, f.worstEdgeUm);
  expectEveryCellItsDose(f);
}

// An index whose kept passes are cut short (the files changed since M29) is refused before any light.
TEST_F(ScanCardTest, AnIndexMissingItsKeptPassesIsAFileErrorBeforeAnyLight) {
  photo(200, 8, 2000);
  ASSERT_TRUE(has(upload("CUT.UVJ", encode(h, g)), "echo:Done saving file."));
  std::string index = m.sd.contents("CUT.UVJ~i");
  m.sd.put("CUT.UVJ~i", index.substr(0, keptPassAt(h.rows, 1)));
  start("CUT.UVJ");
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 20000000);
  EXPECT_EQ(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_TRUE(m.nano.scanLight.empty());
  std::string said;
  for (const std::string& l : m.usbLines)
    if (l.find("E22") != std::string::npos) said = l;
  EXPECT_NE(said, "") << end;
  std::printf("[scan card] an index cut short: %s\n", said.c_str());
}

// A kept pass the card garbled (its CRC-16 no longer that of what it holds) is a file error before
// that pass's light: the pass before it ran, the job pauses with E22 and the LEDs off.
TEST_F(ScanCardTest, AGarbledKeptPassIsAFileErrorBeforeItsLight) {
  photo(200, 8, 2000);
  ASSERT_TRUE(has(upload("BENT.UVJ", encode(h, g)), "echo:Done saving file."));
  std::string index = m.sd.contents("BENT.UVJ~i");
  ASSERT_EQ(index.size(), keptPassAt(h.rows, 2));
  index[keptPassAt(h.rows, 1) + 8] ^= 1;  // pass 1's first column, one off
  m.sd.put("BENT.UVJ~i", index);
  start("BENT.UVJ");
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 20000000);
  EXPECT_EQ(end.rfind("JOB:paused", 0), 0u) << end;
  EXPECT_NE(end.find("stop=1/2"), std::string::npos) << end;
  std::string said;
  for (const std::string& l : m.usbLines)
    if (l.find("E22") != std::string::npos) said = l;
  EXPECT_NE(said, "") << end;
  EXPECT_FALSE(m.nano.scanLight.empty());  // pass 0's
  std::printf("[scan card] a garbled kept pass: %s, after %s\n", said.c_str(), end.c_str());
}

// A scan job planned by a build that kept only each pass's window (its `~s` marked UVP1, an index of
// 4 bytes a pass) is planned again when selected: M23 finds no plan it can read, the new plan keeps
// every pass whole, and the job runs every cell its dose.
TEST_F(ScanCardTest, AJobPlannedByAnOlderBuildIsPlannedAgainWhenSelected) {
  photo(200, 8, 2000);
  ASSERT_TRUE(has(upload("OLD.UVJ", encode(h, g)), "echo:Done saving file."));
  std::string stops = m.sd.contents("OLD.UVJ~s"), index = m.sd.contents("OLD.UVJ~i");
  stops[3] = '1';
  m.sd.put("OLD.UVJ~s", stops);
  m.sd.put("OLD.UVJ~i", index.substr(0, keptPassAt(h.rows, 0) + 8));  // two windows of 4 bytes
  ASSERT_NO_FATAL_FAILURE(runToDone("OLD.UVJ"));
  EXPECT_EQ(m.sd.contents("OLD.UVJ~i"), index);
  EXPECT_EQ(m.sd.contents("OLD.UVJ~s").substr(0, 4), "UVP2");
  expectEveryCellItsDose(measure(scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, m.head.jobBaud()))));
}
