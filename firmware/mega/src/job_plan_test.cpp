// The machine the Mega's planners see (plannerMachine): the settings, and no faster than the step
// engine runs, so a scan pass never flies a stretch faster than the head can step.
#include <gtest/gtest.h>

#include "job_plan.h"
#include "printhead_link.h"
#include "step_profile.h"

using namespace mega;

TEST(PlannerMachine, TopSpeedIsTheSettingOrTheStepEnginesWhicheverIsLess) {
  Config config;  // 80 steps/mm, 100 mm/s: 8000 steps/s
  uv::Machine m = plannerMachine(config, 5, 7, kJobLinkBaud);
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
