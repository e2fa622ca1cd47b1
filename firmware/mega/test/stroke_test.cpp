// A scan pass's stroke (Motion::stroke): ramps at the X axis's acceleration, a middle at an exact
// fractional interval that holds over thousands of steps, and the mark on its step.
#include <gtest/gtest.h>

#include "motion_rig.h"

using namespace mega;

namespace {

struct StrokeTest : ::testing::Test {
  Config config;  // 80 steps/mm, 2000 mm/s², 100 mm/s
  MotionRig rig{config};
};

}  // namespace

TEST_F(StrokeTest, TheMiddleKeepsTheExactIntervalAndTheMarkIsItsStep) {
  // 1000.37 ticks a step: whole ticks would drift 0.37 tick a step, 2220 ticks over 6000 steps.
  const uint16_t interval = 1000, frac = static_cast<uint16_t>(0.37 * 65536);
  const uint32_t ramp = rig.motion.strokeRampSteps(interval, frac);
  ASSERT_GT(ramp, 0u);
  const uint32_t total = 2 * ramp + 6000, mark = ramp + 100;
  ASSERT_TRUE(rig.motion.stroke({static_cast<int32_t>(total), interval, frac, mark}));
  EXPECT_FALSE(rig.motion.stroke({10, interval, frac, 0}));  // one at a time while it is queued
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(0), static_cast<int32_t>(total));
  ASSERT_EQ(rig.steps.size(), total);
  ASSERT_EQ(rig.marks.size(), 1u);
  EXPECT_EQ(rig.marks[0], rig.steps[mark - 1].us2);
  const double exact = interval + frac / 65536.0;
  const uint64_t t0 = rig.steps[ramp].us2;
  for (uint32_t i = ramp; i < total - ramp; i++) {
    const double ideal = t0 + (i - ramp) * exact;
    ASSERT_NEAR(static_cast<double>(rig.steps[i].us2), ideal, 1.0) << "step " << i;
  }
  // The ramps never outrun the middle.
  for (uint32_t i = 1; i < total; i++) ASSERT_GE(rig.steps[i].us2 - rig.steps[i - 1].us2, interval) << i;
  EXPECT_EQ(rig.engine.marks(), 1);
  EXPECT_EQ(rig.engine.marksMissed(), 0);
}

TEST_F(StrokeTest, BackwardsAndOneAfterAnother) {
  const uint32_t ramp = rig.motion.strokeRampSteps(500, 0);
  const int32_t n = static_cast<int32_t>(2 * ramp + 400);
  ASSERT_TRUE(rig.motion.stroke({n, 500, 0, ramp + 1}));
  ASSERT_TRUE(rig.runIdle());
  ASSERT_TRUE(rig.motion.stroke({-n, 500, 0, ramp + 1}));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(0), 0);
  EXPECT_EQ(rig.marks.size(), 2u);
  for (uint32_t i = ramp + 1; i < static_cast<uint32_t>(n) - ramp; i++) ASSERT_EQ(rig.steps[i].us2 - rig.steps[i - 1].us2, 500u) << i;
}

TEST_F(StrokeTest, AStopMidStrokeSlowsDownToRest) {
  const uint32_t ramp = rig.motion.strokeRampSteps(500, 0);
  ASSERT_TRUE(rig.motion.stroke({static_cast<int32_t>(2 * ramp + 20000), 500, 0, 0}));
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(0) > static_cast<int32_t>(ramp + 1000); }, 10000000));
  rig.motion.stop();
  ASSERT_TRUE(rig.runIdle());
  EXPECT_LT(rig.pos(0), static_cast<int32_t>(2 * ramp + 2000));
  // The next stroke may be queued: nothing of the last one is left.
  EXPECT_TRUE(rig.motion.stroke({-100, 500, 0, 0}));
}
