// Paced jobs (protocol/mega.md "Pacing"): M24 P1 waits to cool before a stop near a soft limit
// instead of pausing at it, the JOB: line says so, and it still exposes every stop as planned.
// Also: a JOB: line at its longest goes out whole, and a job's elapsed time outlasts 71 minutes.
#include "machine_job_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
// A job run to its end with the head held at `deciC`, started by `start`: its last JOB: line.
class PacingTest : public JobTest {
 protected:
  std::string runWarm(const std::string& name, const uv::JobHeader& h, const Grid& g, int16_t deciC, const std::string& start) {
    upload(name, encode(h, g));
    m.cmd("M23 " + name);
    m.cmd("G28");
    m.nano.setTemps(deciC);
    m.run(600000);
    EXPECT_EQ(payload(start), Lines{});
    return runUntilJob({"done", "paused"});
  }
};
}  // namespace

TEST_F(JobTest, APacedJobWaitsToCoolNearASoftLimitAndExposesEveryStop) {
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 4);
  upload("P.UVJ", encode(h, g));
  m.cmd("M23 P.UVJ");
  m.cmd("G28");
  m.nano.setTemps(485);  // T4 and T5 at 48.5 °C: within 2 °C of their 50 °C soft limit, under it
  m.run(600000);
  EXPECT_EQ(payload("M24 P1"), Lines{});
  m.run(2000000);
  std::string cooling = lastJob(m.usbLines);
  EXPECT_EQ(cooling.rfind("JOB:running ", 0), 0u) << cooling;
  EXPECT_NE(cooling.find(" paced=1 cooling=1"), std::string::npos) << cooling;
  EXPECT_TRUE(m.nano.exposures.empty());
  m.nano.setTemps(475);  // 47.5: still within 3 °C, so it waits on
  m.run(1200000);
  EXPECT_TRUE(m.nano.exposures.empty());
  m.nano.setTemps(465);  // 46.5: cool enough
  std::string done = runUntilJob({"done", "paused"});
  EXPECT_EQ(done.rfind("JOB:done", 0), 0u) << done;
  EXPECT_NE(done.find(" paced=1"), std::string::npos) << done;
  EXPECT_FALSE(has(m.usbLines, "FAULT:E31"));
  expectExposed(h, plan(h, g));
}

TEST_F(PacingTest, AnUnpacedJobDoesNotWaitNearTheLimitAndPIsZeroOrOne) {
  EXPECT_EQ(payload("M24 P2"), (Lines{"echo:E11 bad or missing parameter: P is 0 or 1"}));
  EXPECT_EQ(payload("M828 P"), (Lines{"echo:E11 bad or missing parameter: P is 0 or 1"}));
  uv::JobHeader h = header(8, 8, uv::Strategy::Raster);
  Grid g = pattern(8, 8, 9);
  std::string done = runWarm("U.UVJ", h, g, 485, "M24");  // T4 at 48.5 °C, within 2 °C of its limit
  EXPECT_EQ(done.rfind("JOB:done", 0), 0u) << done;
  EXPECT_EQ(done.find("paced"), std::string::npos) << done;
  EXPECT_FALSE(has(m.usbLines, "cooling=1"));
  expectExposed(h, plan(h, g));
}

TEST_F(JobTest, ContinuingAThermalPauseWithP1RunsTheRestPaced) {
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 4);
  upload("T.UVJ", encode(h, g));
  m.cmd("M23 T.UVJ");
  m.cmd("G28");
  m.cmd("M24");
  m.run(200000);
  m.nano.setTemps(505);  // over T4's soft limit: an unpaced job pauses
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("reason=overtemp"), std::string::npos) << paused;
  m.nano.setTemps(485);  // below the limit, within 2 °C of it: paced, it waits
  m.run(1200000);
  EXPECT_EQ(payload("M24 P1"), Lines{});
  size_t fired = m.nano.exposures.size();
  m.run(2000000);
  EXPECT_EQ(m.nano.exposures.size(), fired);  // waiting to cool, not exposing
  EXPECT_NE(lastJob(m.usbLines).find("paced=1 cooling=1"), std::string::npos) << lastJob(m.usbLines);
  m.nano.setTemps(400);
  EXPECT_EQ(runUntilJob({"done"}).rfind("JOB:done", 0), 0u);
}

TEST_F(JobTest, TheLongestJobLineGoesOutWholeAndElapsedOutlasts71Minutes) {
  uv::JobHeader h = header(8, 8, uv::Strategy::Raster);
  Grid g = pattern(8, 8, 3);
  const std::string name = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0.UVJ";  // 31 characters, the most a name has
  ASSERT_EQ(name.size(), 31u);
  upload(name, encode(h, g));
  m.cmd("M23 " + name);
  m.cmd("G28");
  m.nano.setTemps(485);
  m.run(600000);
  m.cmd("M24 P1");
  m.run(1000000);
  ASSERT_NE(lastJob(m.usbLines).find("cooling=1"), std::string::npos);
  // Waiting to cool, nothing lit and the head still: 80 minutes pass in 20 s leaps, a host line
  // after each (30 s without one would pause the job).
  for (int i = 0; i < 240; i++) {
    m.nowUs += 20000000;
    m.cmd("M105");
  }
  Lines status = payload("M27");
  ASSERT_EQ(status.size(), 1u);
  uint32_t elapsed = static_cast<uint32_t>(std::stoul(status[0].substr(status[0].find("elapsed=") + 8)));
  EXPECT_GE(elapsed, 80u * 60) << status[0];
  EXPECT_LT(elapsed, 80u * 60 + 30) << status[0];
  EXPECT_NE(status[0].find("cooling=1"), std::string::npos) << status[0];
  m.cmd("M25");
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("file=" + name), std::string::npos) << paused;
  EXPECT_NE(paused.find(" paced=1"), std::string::npos) << paused;
  EXPECT_LE(paused.size(), kJobLineMax - 1u);
  EXPECT_EQ(m.usbLink.txDropped(), 0u);
}
