// A machine that has run for 71.6 minutes, where the boards' 32-bit micros() wraps: a job that spans
// the wrap runs to its end and the printhead link stays up. (Issue 41 item 3: the simulated printer
// at 50x got there during a job and lost its Nano for good, E30 on every poll.)
#include <gtest/gtest.h>

#include <string>

#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {

constexpr uint64_t kWrapUs = uint64_t{1} << 32;

// Powered up this long before the wrap: its setup, the upload and the homing take about 4 s of it,
// so each job below starts short of the wrap and runs across it.
constexpr uint64_t kLeadUs = 5000000;

struct ClockWrapTest : ScanMachineTest {
  void SetUp() override {
    m.nowUs = kWrapUs - kLeadUs;
    ScanMachineTest::SetUp();
  }
  size_t e30s() const {
    size_t n = 0;
    for (const std::string& l : m.usbLines) n += l.find("E30") != std::string::npos;
    return n;
  }
  // After the job: the Nano still answers (M105 reads its sensors, not E30).
  void expectPrintheadUp() {
    m.run(2000000);  // a few of the link's polls past the job
    const Lines t = m.cmd("M105");
    EXPECT_TRUE(has(t, "T:25.0 /0.0 S0:25.0")) << ::testing::PrintToString(t);
    EXPECT_EQ(e30s(), 0u);
  }
};

}  // namespace

TEST_F(ClockWrapTest, AStopAndFireJobRunsAcrossTheWrapOfMicrosToItsEnd) {
  uv::JobHeader h = header(30, 20, uv::Strategy::Serpentine);
  Grid g = pattern(30, 20, 41);
  const size_t from = m.nano.exposures.size();
  ASSERT_TRUE(has(uploadAndStart("WRAP.UVJ", encode(h, g)), "echo:Done saving file."));
  const uint64_t startedUs = m.nowUs;
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  std::printf("[clock wrap] stop and fire: job from %.2f s before the wrap to %.2f s after it\n", (kWrapUs - startedUs) / 1e6,
              (m.nowUs - kWrapUs) / 1e6);
  ASSERT_LT(startedUs, kWrapUs);  // else the lead above no longer puts the wrap inside the job
  ASSERT_GT(m.nowUs, kWrapUs);
  const std::vector<uv::Stop> stops = plan(h, g);
  EXPECT_EQ(end.rfind("JOB:done file=WRAP.UVJ stop=" + std::to_string(stops.size()) + "/" + std::to_string(stops.size()), 0), 0u) << end;
  expectExposed(h, stops, from);
  expectPrintheadUp();
}

TEST_F(ClockWrapTest, AScanJobRunsAcrossTheWrapOfMicrosEveryCellItsDose) {
  job(40, 60, 2000);
  ASSERT_TRUE(has(upload("SCAN.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 SCAN.UVJ");
  m.cmd("G28");
  m.rig.steps.clear();  // the track starts at the origin
  m.cmd("M24");
  const uint64_t startedUs = m.nowUs;
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  std::printf("[clock wrap] scan: job from %.2f s before the wrap to %.2f s after it\n", (kWrapUs - startedUs) / 1e6,
              (m.nowUs - kWrapUs) / 1e6);
  ASSERT_LT(startedUs, kWrapUs);
  ASSERT_GT(m.nowUs, kWrapUs);
  ASSERT_EQ(end.rfind("JOB:done", 0), 0u) << end;
  const scandose::Figures f = measure(2000);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  expectPrintheadUp();
}

// A host that opens the port (DTR resets the Mega) on a printer past the wrap: its first M105 reads
// the sensors. (Before the rig kept its wire on 64-bit time, printcore printed E30 right after opening.)
TEST_F(ClockWrapTest, AHostThatOpensThePortAfterTheWrapFindsThePrinthead) {
  m.run(kLeadUs + 1000000);
  ASSERT_GT(m.nowUs, kWrapUs);
  m.reset(100000);
  EXPECT_TRUE(has(m.cmd("M105"), "T:25.0 /0.0 S0:25.0"));
  EXPECT_EQ(e30s(), 0u);
}
