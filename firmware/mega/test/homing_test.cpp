// Homing and the kinematic self-test, run through the motion code and the step interrupt's code in
// simulated time, with endstop switches that close at given positions.
#include <gtest/gtest.h>

#include "homing.h"
#include "motion_rig.h"
#include "selftest.h"

using namespace mega;

namespace {

class HomingTest : public ::testing::Test {
 protected:
  Config config;
  MotionRig rig{config};
  Homing homing{rig.motion, config};
  SelfTest test{rig.motion, config};

  // Runs a routine to its end; the main loop reads the switches as the interrupt does.
  template <typename Poll>
  RoutineStatus run(Poll poll) {
    RoutineStatus s = RoutineStatus::Running;
    rig.runUntil([&] { return (s = poll()) != RoutineStatus::Running; }, 120000000);
    return s;
  }
  RoutineStatus home(uint8_t axes) {
    homing.start(axes);
    return run([&] { return homing.poll(rig.endstops()); });
  }
  void startAt(int32_t x, int32_t y, int32_t z) {
    int32_t p[3] = {x, y, z};
    rig.motion.setPositionSteps(p);
  }
};

}  // namespace

TEST_F(HomingTest, EachAxisEndsExactlyWhereItsSwitchClosesZFirst) {
  // The head starts somewhere unknown: the switches sit at these counts.
  startAt(0, 0, 0);
  rig.switchAt[0] = -9137;
  rig.switchAt[1] = -4021;
  rig.switchAt[2] = -777;
  ASSERT_EQ(home(7), RoutineStatus::Done);
  EXPECT_EQ(homing.homed(), 7);
  int32_t p[3];
  rig.motion.positionSteps(p);
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[1], 0);
  EXPECT_EQ(p[2], 0);
  // Net travel per axis is exactly to the switch: Z moved first.
  int32_t moved[3] = {0, 0, 0};
  int firstAxis = -1;
  for (const StepEvent& e : rig.steps)
    for (uint8_t a = 0; a < 3; a++)
      if (e.axes & (1 << a)) {
        moved[a] += (e.dirNeg & (1 << a)) ? -1 : 1;
        if (firstAxis < 0) firstAxis = a;
      }
  EXPECT_EQ(firstAxis, 2);
  EXPECT_EQ(moved[0], -9137);
  EXPECT_EQ(moved[1], -4021);
  EXPECT_EQ(moved[2], -777);
}

TEST_F(HomingTest, TheSlowSeekFindsTheSwitchAgainAfterAnExactBackoff) {
  rig.switchAt[0] = -3000;
  ASSERT_EQ(home(1), RoutineStatus::Done);
  // The last steps: away 160 steps (2 mm), then back 160 at a tenth of the speed.
  ASSERT_GE(rig.steps.size(), 320u);
  size_t n = rig.steps.size();
  int away = 0, back = 0;
  for (size_t i = n - 320; i < n; i++) ((rig.steps[i].dirNeg & 1) ? back : away)++;
  EXPECT_EQ(away, 160);
  EXPECT_EQ(back, 160);
  // 40 mm/s / 10 = 4 mm/s = 320 steps/s while creeping in.
  EXPECT_NEAR(2e6 / rig.steps[n - 2].interval, 320, 4);
  EXPECT_EQ(homing.homed(), 1);
}

TEST_F(HomingTest, AnAxisOnItsSwitchBacksOffFirst) {
  rig.switchAt[1] = 50;  // closed now
  ASSERT_EQ(home(2), RoutineStatus::Done);
  EXPECT_EQ(rig.pos(1), 0);
}

TEST_F(HomingTest, AMissingOrStuckSwitchFailsWithE44AndNamesTheAxis) {
  rig.switchAt[2] = INT32_MIN;  // never closes: the seek runs the whole travel
  ASSERT_EQ(home(4), RoutineStatus::Failed);
  EXPECT_EQ(homing.error(), 44);
  EXPECT_EQ(homing.failedAxis(), 2);
  EXPECT_EQ(homing.homed(), 0);
  EXPECT_LE(rig.pos(2), -(40 + 10) * 400);  // it went the bed's length and 10 mm

  MotionRig stuck{config};
  Homing h{stuck.motion, config};
  stuck.switchAt[0] = INT32_MAX;  // always closed
  h.start(1);
  RoutineStatus s = RoutineStatus::Running;
  stuck.runUntil([&] { return (s = h.poll(stuck.endstops())) != RoutineStatus::Running; }, 60000000);
  EXPECT_EQ(s, RoutineStatus::Failed);
  EXPECT_EQ(h.failedAxis(), 0);
}

TEST_F(HomingTest, TheQuickSelfTestCountsEveryStepBack) {
  rig.switchAt[0] = rig.switchAt[1] = -123;
  ASSERT_EQ(home(3), RoutineStatus::Done);  // the head stays on the switches, its count 0 there
  test.start(true);
  ASSERT_EQ(run([&] { return test.poll(); }), RoutineStatus::Done);
  EXPECT_TRUE(test.allPass());
  EXPECT_EQ(test.counted(0), 1600u);
  EXPECT_EQ(test.counted(1), 1600u);
  char line[80];
  test.format(line);
  EXPECT_STREQ(line, "TEST:quick x=pass x_steps=1600 y=pass y_steps=1600");
}

TEST_F(HomingTest, TheFullSelfTestFailsAnAxisThatLostSteps) {
  rig.switchAt[0] = rig.switchAt[1] = 0;
  ASSERT_EQ(home(3), RoutineStatus::Done);
  test.start(false);
  // On the way out, Y's belt slips 24 steps (0.3 mm): the carriage is nearer its switch than counted.
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(1) >= 8000; }, 60000000));
  rig.switchAt[1] = 24;
  ASSERT_EQ(run([&] { return test.poll(); }), RoutineStatus::Done);
  EXPECT_TRUE(test.pass(0));
  EXPECT_FALSE(test.pass(1));
  EXPECT_EQ(test.counted(0), 16000u);
  EXPECT_EQ(test.counted(1), 16000u - 24u);
  char line[80];
  test.format(line);
  EXPECT_STREQ(line, "TEST:full x=pass x_steps=16000 y=fail y_steps=15976");
}
