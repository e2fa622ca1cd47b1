// A paced continue of a job paused hot (protocol/mega.md "Pacing"): M24 P1 is taken and waits to cool,
// dark and still, until every reading is 3 °C under its soft limit and the Nano's OVERTEMP flag is
// clear; a plain continue while hot, a broken sensor and a silent printhead are still refused.
#include "machine_job_fixture.h"

using namespace mega;
using namespace jobs;

namespace {
const Lines kHot = {"Error:E31 over-temperature: printhead faulted"};

class PacedContinueTest : public JobTest {
 protected:
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 4);

  // Starts the job unpaced and heats the head to `deciC` until it pauses; returns the JOB:paused line.
  std::string pauseHot(int16_t deciC) {
    uploadAndStart("H.UVJ", encode(h, g));
    m.run(200000);
    m.nano.setTemps(deciC);
    std::string paused = runUntilJob({"paused"});
    EXPECT_NE(paused.find("reason=overtemp"), std::string::npos) << paused;
    return paused;
  }
  // Every sensor at `deciC`, the readings and the Nano's flags come to the Mega (T and E, every 500 ms).
  void holdAt(int16_t deciC) {
    m.nano.setTemps(deciC);
    m.run(1200000);
  }
  // The rest of the job, from the stop its JOB:paused line names, exposed as planned from exposure `from`.
  void expectTheRestExposed(const std::string& paused, size_t from) {
    size_t at = paused.find(" stop=") + 6;
    std::vector<uv::Stop> all = plan(h, g);
    std::vector<uv::Stop> rest(all.begin() + std::stol(paused.substr(at)), all.end());
    expectExposed(h, rest, from);
  }
};
}  // namespace

TEST_F(PacedContinueTest, APacedContinueWaitsForTheReadingsAndTheNanosFlagThenExposesTheRest) {
  // Soft limits at the Nano's own 60 °C: its OVERTEMP flag, which clears only under 55, then stands
  // while every reading is already 3 °C under its soft limit.
  for (int i = 0; i < 6; i++) m.cmd("M850 thermal.limit." + std::to_string(i) + " 60");
  std::string paused = pauseHot(610);
  holdAt(620);
  EXPECT_EQ(payload("M24"), kHot);  // unpaced: refused, as ever
  const size_t fired = m.nano.exposures.size();
  const int32_t at[3] = {m.rig.head[0], m.rig.head[1], m.rig.head[2]};
  EXPECT_EQ(payload("M24 P1"), Lines{});  // taken: the wait to cool comes first
  m.run(1000000);
  std::string cooling = lastJob(m.usbLines);
  EXPECT_EQ(cooling.rfind("JOB:running ", 0), 0u) << cooling;
  EXPECT_NE(cooling.find(" paced=1 cooling=1"), std::string::npos) << cooling;
  holdAt(565);  // 3.5 °C under the soft limits, but over the 55 °C under which the Nano's flag clears
  m.run(3000000);
  EXPECT_NE(lastJob(m.usbLines).find(" cooling=1"), std::string::npos) << lastJob(m.usbLines);
  EXPECT_EQ(m.nano.exposures.size(), fired);  // dark
  for (int a = 0; a < 3; a++) EXPECT_EQ(m.rig.head[a], at[a]) << "axis " << a;  // still
  EXPECT_EQ(payload("M24 P1"), (Lines{"echo:E12 not allowed while a job is running"}));  // running: not paused
  m.nano.setTemps(545);  // the flag clears
  std::string done = runUntilJob({"done", "paused"});
  EXPECT_EQ(done.rfind("JOB:done", 0), 0u) << done;
  EXPECT_NE(done.find(" paced=1"), std::string::npos) << done;
  expectTheRestExposed(paused, fired);
}

TEST_F(PacedContinueTest, ARunningPacedJobWaitsForTheNanosFlagNotOnlyForTheReadings) {
  for (int i = 0; i < 6; i++) m.cmd("M850 thermal.limit." + std::to_string(i) + " 60");
  upload("H.UVJ", encode(h, g));
  m.cmd("M23 H.UVJ");
  m.cmd("G28");
  holdAt(585);  // within 2 °C of the 60 °C soft limits: the job waits before its first stop
  EXPECT_EQ(payload("M24 P1"), Lines{});
  m.run(2000000);
  ASSERT_NE(lastJob(m.usbLines).find(" cooling=1"), std::string::npos) << lastJob(m.usbLines);
  holdAt(605);  // the Nano's flag set while it waits
  holdAt(565);  // the readings cool enough; the flag stands until under 55 °C
  m.run(3000000);
  EXPECT_TRUE(m.nano.exposures.empty());
  EXPECT_NE(lastJob(m.usbLines).find(" cooling=1"), std::string::npos) << lastJob(m.usbLines);
  m.nano.setTemps(545);
  std::string done = runUntilJob({"done", "paused"});
  EXPECT_EQ(done.rfind("JOB:done", 0), 0u) << done;  // never paused for the flag
  expectExposed(h, plan(h, g));
}

TEST_F(PacedContinueTest, ABrokenSensorOrASilentPrintheadIsStillRefusedAndAPlainContinueWaitsForTheCool) {
  pauseHot(560);  // over the 55 °C soft limits, under the Nano's 60
  EXPECT_EQ(payload("M24"), kHot);
  EXPECT_EQ(payload("M24 P0"), kHot);
  const int16_t broken[6] = {560, -500, 560, 560, 560, 560};  // T1 open: cooling never clears it
  m.nano.setTemps(broken);
  m.run(1200000);
  EXPECT_EQ(payload("M24 P1"), (Lines{"Error:E32 temperature sensor fault"}));
  m.nano.silent = true;
  m.run(3000000);
  EXPECT_EQ(payload("M24 P1"), (Lines{"Error:E30 printhead not responding"}));
  m.nano.silent = false;
  holdAt(300);
  EXPECT_EQ(lastJob(m.usbLines).rfind("JOB:paused", 0), 0u) << lastJob(m.usbLines);
  EXPECT_EQ(payload("M24"), Lines{});
  EXPECT_EQ(runUntilJob({"done", "paused"}).rfind("JOB:done", 0), 0u);
}

TEST_F(PacedContinueTest, M25DuringTheWaitPausesAndASensorThatBreaksMeanwhileFailsItDark) {
  pauseHot(560);
  const size_t fired = m.nano.exposures.size();
  EXPECT_EQ(payload("M24 P1"), Lines{});
  m.run(1000000);
  ASSERT_NE(lastJob(m.usbLines).find(" cooling=1"), std::string::npos) << lastJob(m.usbLines);
  m.cmd("M25");
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("reason=user"), std::string::npos) << paused;
  EXPECT_EQ(paused.find("cooling"), std::string::npos) << paused;
  EXPECT_EQ(payload("M24 P1"), Lines{});  // still hot: it waits again
  m.run(1000000);
  ASSERT_NE(lastJob(m.usbLines).find(" cooling=1"), std::string::npos) << lastJob(m.usbLines);
  const int16_t broken[6] = {560, -500, 560, 560, 560, 560};
  m.nano.setTemps(broken);
  paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("reason=fault"), std::string::npos) << paused;
  EXPECT_TRUE(has(m.usbLines, "FAULT:E32"));
  EXPECT_EQ(m.nano.exposures.size(), fired);
  EXPECT_EQ(m.nano.lit(), 0);
}
