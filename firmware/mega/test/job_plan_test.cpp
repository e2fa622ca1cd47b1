// The machine the Mega's planners see (plannerMachine): the settings, and no faster than the step
// engine runs, so a scan pass never flies a stretch faster than the head can step; and the link
// speed a scan job's stop file keeps.
#include <gtest/gtest.h>

#include "job_plan.h"
#include "printhead_link.h"
#include "step_profile.h"
#include "stop_file.h"
#include "storage_fake.h"

using namespace mega;

TEST(PlannerMachine, TopSpeedIsTheSettingOrTheStepEnginesWhicheverIsLess) {
  Config config;  // 80 steps/mm, 100 mm/s: 8000 steps/s
  uv::MotionModel m = plannerMachine(config, 5, 7, kJobLinkBaud);
  EXPECT_EQ(m.vmaxUmS[0], 100000u);
  EXPECT_EQ(m.vmaxUmS[1], 100000u);
  EXPECT_EQ(m.startUm[0], 5);
  EXPECT_EQ(m.startUm[1], 7);
  // A leadscrew at 1/16 microstepping on X: 400 steps/mm, where 100 mm/s would be 40000 steps/s.
  ASSERT_TRUE(config.set(Key::StepsX, "400", 3));
  m = plannerMachine(config, 0, 0, kJobLinkBaud);
  EXPECT_EQ(m.vmaxUmS[0], kMaxStepRate * 1000000ull / 400000);  // 40 mm/s
  EXPECT_EQ(m.vmaxUmS[1], 100000u);
}

// A scan job's stop file keeps the link speed it was planned at, after the job's header, and how many
// pass windows its index holds; a speed the link cannot take is read as a broken file (the job is
// planned again at M23), never used.
TEST(StopFile, AScanJobsFileKeepsTheLinkSpeedItWasPlannedAt) {
  FakeStorage sd;
  uv::JobHeader job{};
  job.cols = 12;
  StopFileHeader h{};
  h.scan = true;
  h.count = 3;
  for (uint32_t baud : {115200u, 250000u, 115201u, 0u}) {
    FileHandle f = sd.open("J~s", Storage::Mode::Create);
    ASSERT_GE(f, 0);
    ASSERT_TRUE(writeStopHeader(sd, f, h));
    ASSERT_TRUE(writeScanHeader(sd, f, job, baud, 3));
    sd.close(f);
    f = sd.open("J~s", Storage::Mode::Read);
    StopFileHeader back{};
    uv::JobHeader jobBack{};
    uint32_t linkBaud = 1, windows = 0;
    ASSERT_TRUE(readStopHeader(sd, f, back));
    EXPECT_EQ(readScanHeader(sd, f, jobBack, linkBaud, windows), baud == 115200u || baud == 250000u) << baud;
    EXPECT_EQ(linkBaud, baud);
    EXPECT_EQ(windows, 3u);
    EXPECT_EQ(jobBack.cols, 12);
    sd.close(f);
  }
}
