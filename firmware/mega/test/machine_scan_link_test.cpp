// Scan jobs and the printhead link's speed (protocol/nano.md "Link speed"): each job is planned at
// the speed the link has or will have (PrintheadLink::jobBaud()) and runs at it. A Nano reset mid-job
// takes the link back to 115200 and cuts the pass; the resumed job waits for the raise; a Nano that
// never takes L runs its jobs planned at 115200; a raise that fails mid-job stops the job with E34.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "job_files.h"
#include "job_plan.h"
#include "le_bytes.h"
#include "machine_scan_fixture.h"
#include "stop_file.h"

using namespace mega;
using namespace jobs;

namespace {
struct ScanLinkTest : ScanMachineTest {
  // The link speed a card job's stop file says it was planned at (stop_file.h: after the job's header).
  uint32_t plannedBaud(const char* job) {
    char work[kWorkNameMax + 1];
    workFileName(job, JobFile::Stops, work);
    const std::string s = m.sd.contents(work);
    if (s.size() != kStopHeaderBytes + sizeof(uv::JobHeader) + 8) return 0;  // the speed, then the windows kept
    return getLe32(s.data() + kStopHeaderBytes + sizeof(uv::JobHeader));
  }
  // The Nano restarts as one that never answers L: the Mega, back at 115200, asks again and gives up.
  void neverTakesL() {
    m.nano.noRaise = true;
    m.nano.powerCycle();
    for (int i = 0; i < 1500 && !m.head.raiseFailed(); i++) m.run(10000);
    ASSERT_TRUE(m.head.raiseFailed());
    ASSERT_EQ(m.head.jobBaud(), uv::kNanoBaud);
    ASSERT_FALSE(m.head.raised());
  }
};
}  // namespace

TEST_F(ScanLinkTest, ANanoResetMidJobFallsBackTo115200AndTheResumedJobRunsRaisedAgain) {
  ASSERT_EQ(kJobLinkBaud, kNanoFastBaud);  // the board raises the link, and plans jobs at it
  EXPECT_EQ(m.head.jobBaud(), kNanoFastBaud);
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("L.UVJ", encode(h, g)), "echo:Done saving file."));
  start("L.UVJ");
  ASSERT_NE(runUntilJob({"running file=L.UVJ stop=1/3"}, 20000000), "(none)");  // into the second pass
  ASSERT_TRUE(lightOn());
  EXPECT_TRUE(m.head.raised());
  EXPECT_EQ(m.nano.megaBaud(), kNanoFastBaud);
  const size_t raises = static_cast<size_t>(std::count(m.nano.lines.begin(), m.nano.lines.end(), "L:250000"));
  m.nano.powerCycle();  // the Nano restarts mid-pass: LEDs dark, at 115200 from its first instruction
  EXPECT_EQ(m.nano.nanoBaud(), uv::kNanoBaud);
  const std::string stopped = runUntilJob({"paused", "failed", "done", "aborted"}, 5000000);
  std::printf("[scan link] a Nano reset mid-pass: %s\n", stopped.c_str());
  ASSERT_NE(stopped.find("stop=1/3"), std::string::npos) << stopped;  // the cut pass is not counted
  // The Mega fell back to 115200 at its first unanswered line, and hears the Nano again there.
  EXPECT_EQ(m.nano.megaBaud(), uv::kNanoBaud);
  EXPECT_FALSE(m.head.raised());
  EXPECT_EQ(m.head.baud(), uv::kNanoBaud);
  EXPECT_EQ(m.nano.lit(), 0);
  m.cmd("M24");  // at once: the link is still at 115200, and the pass waits for the raise
  m.run(100000);
  EXPECT_EQ(m.nano.lit(), 0);
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_NE(end.find("stop=3/3"), std::string::npos) << end;
  EXPECT_TRUE(m.head.raised());  // raised again once idle, before the resumed pass went
  EXPECT_GT(static_cast<size_t>(std::count(m.nano.lines.begin(), m.nano.lines.end(), "L:250000")), raises);
  // The first and third passes' cells got their dose once; the second's at least once.
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

// A Nano that never takes L (firmware from before it, or a wiring that fails at 250000): the link
// stays at 115200, jobs are planned at 115200 (the card's stop file keeps it), and a photo's passes,
// slowed for the slower link, run whole with every cell within 2 % of its dose.
TEST_F(ScanLinkTest, ANanoThatNeverTakesLRunsAPhotoPlannedAt115200EveryCellItsDose) {
  neverTakesL();
  photo(200, 8, 2000);
  ASSERT_TRUE(has(upload("SLOWLINK.UVJ", encode(h, g)), "echo:Done saving file."));
  EXPECT_EQ(plannedBaud("SLOWLINK.UVJ"), uv::kNanoBaud);
  const std::vector<double> windows = scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, uv::kNanoBaud));
  const std::vector<double> raised = scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, kNanoFastBaud));
  EXPECT_GT(windows[0], raised[0]);  // the slower link slows the passes more
  ASSERT_NO_FATAL_FAILURE(runToDone("SLOWLINK.UVJ"));
  EXPECT_FALSE(m.head.raised());
  EXPECT_EQ(m.nano.megaBaud(), uv::kNanoBaud);
  const scandose::Figures f = measure(windows);
  std::printf("[scan link] a Nano that never takes L: a photo at 115200 (windows %.0f us, %.0f raised): worst dose error %.2f %% of full, worst edge %.2f um\n",
              windows[0], raised[0], f.worstDosePct, f.worstEdgeUm);
  expectEveryCellItsDose(f);
}

// The same Nano, a job streamed: planned at 115200 as it arrives, and every cell within 2 %.
TEST_F(ScanLinkTest, ANanoThatNeverTakesLRunsAStreamedScanJobAt115200) {
  neverTakesL();
  job(40, 10, 2000);
  stream();
  const std::string end = runUntilJob({"done", "failed", "paused", "aborted"}, 60000000);
  ASSERT_EQ(end.rfind("JOB:done", 0), 0u) << end;
  const scandose::Figures f = measure(2000);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
}

// A job planned at 250000 whose link falls back and will not rise again (the Nano, reset mid-job, now
// refuses L): the pass waits for the raise as long as kScanClockWaitUs, then the job stops with E34,
// which names the cause, dark. Continued once the link takes the raise again, it ends whole.
TEST_F(ScanLinkTest, AJobPlannedRaisedWhoseLinkWillNotRiseAgainStopsWithE34AndContinuesOnceItDoes) {
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("E34.UVJ", encode(h, g)), "echo:Done saving file."));
  EXPECT_EQ(plannedBaud("E34.UVJ"), kNanoFastBaud);
  start("E34.UVJ");
  ASSERT_NE(runUntilJob({"running file=E34.UVJ stop=1/3"}, 20000000), "(none)");
  ASSERT_TRUE(lightOn());
  m.nano.noRaise = true;
  m.nano.powerCycle();
  ASSERT_NE(runUntilJob({"paused", "failed", "done", "aborted"}, 5000000).find("stop=1/3"), std::string::npos);
  m.cmd("M24");
  const std::string stopped = runUntilJob({"paused", "failed", "done", "aborted"}, 30000000);
  EXPECT_NE(stopped.find("stop=1/3"), std::string::npos) << stopped;
  EXPECT_TRUE(has(m.usbLines, "FAULT:E34 printhead link not at the job's planned speed at stop 1")) << ::testing::PrintToString(m.usbLines);
  EXPECT_TRUE(m.head.raiseFailed());
  EXPECT_EQ(m.nano.lit(), 0);
  m.nano.noRaise = false;  // the Nano takes L again (say, its wiring fixed): the next raise holds
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "paused", "failed"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  EXPECT_TRUE(m.head.raised());
}

// A job planned at 115200 runs at its plan whatever the link does: here the link is raised again
// (the Nano takes L once more) before it runs, and a photo's passes go at their 115200 windows (not
// the shorter ones a plan at 250000 lays out), every cell within 2 %.
TEST_F(ScanLinkTest, AJobPlannedAt115200RunsAsPlannedOnceTheLinkIsRaised) {
  neverTakesL();
  photo(200, 8, 2000);
  const std::vector<double> windows = scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, uv::kNanoBaud));
  const std::vector<double> raised = scandose::passWindows(h, g, plannerMachine(m.config, 0, 0, kNanoFastBaud));
  ASSERT_GT(windows[0], raised[0]);
  ASSERT_TRUE(has(upload("P115.UVJ", encode(h, g)), "echo:Done saving file."));
  EXPECT_EQ(plannedBaud("P115.UVJ"), uv::kNanoBaud);
  m.nano.noRaise = false;
  for (int i = 0; i < 700 && !m.head.raised(); i++) m.run(10000);
  ASSERT_TRUE(m.head.raised());
  EXPECT_EQ(m.head.jobBaud(), kNanoFastBaud);  // a job planned now would be costed raised
  ASSERT_NO_FATAL_FAILURE(runToDone("P115.UVJ"));  // planned at M29: not planned again
  EXPECT_EQ(m.nano.megaBaud(), kNanoFastBaud);
  const scandose::Figures f = measure(windows);
  expectEveryCellItsDose(f);
  // The head crossed each pass at the 115200 plan's speed: its pass took the 115200 windows' time.
  std::printf("[scan link] a photo planned at 115200, run with the link raised: windows %.0f us (%.0f if planned raised), worst dose error %.2f %% of full\n",
              windows[0], raised[0], f.worstDosePct);
}
