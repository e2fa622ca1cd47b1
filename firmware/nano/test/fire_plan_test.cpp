// Host tests of the fire planner.
#include "fire_plan.h"

#include <gtest/gtest.h>

using namespace nano;

namespace {
uv::NanoCommand fireCmd(uint8_t mask, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  uv::NanoCommand cmd{};
  cmd.op = 'F';
  cmd.mask = mask;
  cmd.durations[0] = a;
  cmd.durations[1] = b;
  cmd.durations[2] = c;
  cmd.durations[3] = d;
  return cmd;
}
}  // namespace

TEST(FirePlan, OrdersOffsAndGroupsEqualDurations) {
  FirePlan p;
  ASSERT_EQ(planFire(fireCmd(15, 300, 10, 300, 2000000), 10000000, p), FireVerdict::Fire);
  EXPECT_EQ(p.onMask, 15);
  ASSERT_EQ(p.count, 3);
  EXPECT_EQ(p.events[0].tick, 10u * kTicksPerUs);
  EXPECT_EQ(p.events[0].mask, 2);
  EXPECT_EQ(p.events[1].tick, 300u * kTicksPerUs);
  EXPECT_EQ(p.events[1].mask, 5);
  EXPECT_EQ(p.events[2].tick, 2000000u * kTicksPerUs);
  EXPECT_EQ(p.events[2].mask, 8);
}

TEST(FirePlan, MaskAndZeroDurationsSelectLeds) {
  FirePlan p;
  ASSERT_EQ(planFire(fireCmd(5, 100, 200, 0, 400), 10000000, p), FireVerdict::Fire);
  EXPECT_EQ(p.onMask, 1);  // LED 1 and 3 are not in the mask, LED 2 has no time
  EXPECT_EQ(p.count, 1);
  EXPECT_EQ(planFire(fireCmd(0, 1, 1, 1, 1), 10000000, p), FireVerdict::Nothing);
  EXPECT_EQ(planFire(fireCmd(15, 0, 0, 0, 0), 10000000, p), FireVerdict::Nothing);
}

TEST(FirePlan, RefusesWholeCommandOverTheCap) {
  FirePlan p;
  EXPECT_EQ(planFire(fireCmd(3, 100, 10000001, 0, 0), 10000000, p), FireVerdict::Capped);
  EXPECT_EQ(planFire(fireCmd(1, 10000000, 0, 0, 0), 10000000, p), FireVerdict::Fire);
  // A capped duration outside the mask does not count.
  EXPECT_EQ(planFire(fireCmd(1, 100, 4294967295u, 0, 0), 10000000, p), FireVerdict::Fire);
}
