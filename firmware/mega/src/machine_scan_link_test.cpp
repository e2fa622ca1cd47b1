// A scan job on the card with the printhead link raised (protocol/nano.md "Link speed"; every job is
// planned at printhead_link.h's kJobLinkBaud): a Nano reset mid-job takes the link back to 115200 and
// cuts the pass; the resumed job waits until the link is raised again, and every cell gets its dose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "job_plan.h"
#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
using ScanLinkTest = ScanMachineTest;
}  // namespace

TEST_F(ScanLinkTest, ANanoResetMidJobFallsBackTo115200AndTheResumedJobRunsRaisedAgain) {
  ASSERT_EQ(kJobLinkBaud, kNanoFastBaud);  // the board raises the link, and plans every job at it
  EXPECT_EQ(plannerMachine(m.config, 0, 0).linkBaud, kNanoFastBaud);
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("L.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 L.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();
  m.cmd("M24");
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
