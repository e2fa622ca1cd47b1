// Paced scan jobs (protocol/mega.md "Pacing", issue 41): the Mega waits to cool between passes,
// before the move to the next, with the LEDs off and the head still, instead of pausing in a pass;
// a pause asked for while it waits comes before the pass; a stream paused hot and continued paced
// waits the same way; every cell still gets its dose.
#include <gtest/gtest.h>

#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
struct ScanPacingTest : ScanMachineTest {
  // Runs until a JOB: line reports `stop` (a stream's total grows as its passes are planned).
  bool runUntilStop(const std::string& stop) {
    for (size_t from = m.usbLines.size(), t = 0; t < 20000; t++) {
      m.run(1000);
      for (; from < m.usbLines.size(); from++)
        if (m.usbLines[from].rfind("JOB:running", 0) == 0 && m.usbLines[from].find(" stop=" + stop) != std::string::npos) return true;
    }
    return false;
  }
};
}  // namespace

TEST_F(ScanPacingTest, APacedScanJobWaitsBetweenPassesStillAndDarkThenExposesEveryCell) {
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("PS.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 PS.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();
  m.nano.setTemps(485);  // 48.5 °C: within 2 °C of the 50 °C soft limits of T4 and T5
  m.run(600000);
  EXPECT_EQ(payload("M24 P1"), Lines{});
  m.run(2000000);
  std::string cooling = lastJob(m.usbLines);
  EXPECT_NE(cooling.find("JOB:running file=PS.UVJ stop=0/3"), std::string::npos) << cooling;
  EXPECT_NE(cooling.find(" paced=1 cooling=1"), std::string::npos) << cooling;
  EXPECT_TRUE(m.nano.scanLight.empty());
  EXPECT_TRUE(m.rig.steps.empty());  // before the pass's move: the head has not left
  m.cmd("M25");  // a pause while it waits comes before the pass
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("stop=0/3"), std::string::npos) << paused;
  EXPECT_TRUE(m.nano.scanLight.empty());
  m.cmd("M24 P1");
  m.run(1200000);
  EXPECT_NE(lastJob(m.usbLines).find("cooling=1"), std::string::npos) << lastJob(m.usbLines);
  m.nano.setTemps(475);  // 47.5: still within 3 °C, so it waits on
  m.run(1200000);
  EXPECT_TRUE(m.nano.scanLight.empty());
  m.nano.setTemps(465);  // 46.5: cool enough
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_EQ(end.rfind("JOB:done file=PS.UVJ stop=3/3", 0), 0u) << end;
  EXPECT_NE(end.find(" paced=1"), std::string::npos) << end;
  EXPECT_FALSE(has(m.usbLines, "FAULT:E31"));
  const scandose::Figures f = measure(2000);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
}

TEST_F(ScanPacingTest, AStreamedPacedScanWaitsBeforeThePassThatWouldStartNearTheLimit) {
  job(40, 10, 20000);  // 20 ms a 100 µm cell: 5 mm/s, a pass of about a second
  m.nano.setTemps(250);
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  m.rig.steps.clear();
  m.cmd("M828 P1");
  for (const std::string& r : encode(h, g)) m.cmd(r);
  m.cmd("M29");
  ASSERT_TRUE(runUntilStop("1/"));  // into the second pass
  m.nano.setTemps(490);  // the head near its limit while the second pass runs: the third waits for it
  ASSERT_TRUE(runUntilStop("2/"));
  m.run(1500000);
  std::string cooling = lastJob(m.usbLines);
  EXPECT_NE(cooling.find(" stop=2/"), std::string::npos) << cooling;
  EXPECT_NE(cooling.find("cooling=1"), std::string::npos) << cooling;
  const size_t lit = m.nano.scanLight.size();
  m.run(1500000);
  EXPECT_EQ(m.nano.scanLight.size(), lit);  // dark while it waits
  m.nano.setTemps(460);
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_EQ(end.rfind("JOB:done", 0), 0u) << end;
  EXPECT_NE(end.find(" stop=3/3"), std::string::npos) << end;
  EXPECT_FALSE(has(m.usbLines, "FAULT:E31"));
  const scandose::Figures f = measure(20000);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
}

TEST_F(ScanPacingTest, AStreamPausedHotAndContinuedPacedWaitsStillAndDarkBeforeItsNextPass) {
  job(40, 10, 20000);
  m.nano.setTemps(250);
  ASSERT_TRUE(has(m.cmd("G28"), "ok"));
  m.rig.steps.clear();
  m.cmd("M828");  // unpaced
  for (const std::string& r : encode(h, g)) m.cmd(r);
  m.cmd("M29");
  ASSERT_TRUE(runUntilStop("1/"));
  m.nano.setTemps(510);  // over T4's and T5's 50 °C soft limit: the stream pauses before its next pass
  const std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find(" stop=2/"), std::string::npos) << paused;
  EXPECT_NE(paused.find("reason=overtemp"), std::string::npos) << paused;
  EXPECT_EQ(payload("M24"), (Lines{"Error:E31 over-temperature: printhead faulted"}));
  EXPECT_EQ(payload("M24 P1"), Lines{});  // taken: it waits to cool first
  m.run(1500000);
  EXPECT_NE(lastJob(m.usbLines).find(" paced=1 cooling=1"), std::string::npos) << lastJob(m.usbLines);
  const size_t lit = m.nano.scanLight.size(), stepped = m.rig.steps.size();
  m.run(1500000);
  EXPECT_EQ(m.nano.scanLight.size(), lit);  // dark
  EXPECT_EQ(m.rig.steps.size(), stepped);   // still
  m.nano.setTemps(460);
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_EQ(end.rfind("JOB:done", 0), 0u) << end;
  EXPECT_NE(end.find(" stop=3/3"), std::string::npos) << end;
  const scandose::Figures f = measure(20000);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
}
