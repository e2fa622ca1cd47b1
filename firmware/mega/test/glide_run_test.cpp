// A glide (glide.h, Motion::glide) on the step engine: Y steps on their own timing, alone or beside a
// stroke's run-out, which keeps every X step where it was.
#include <gtest/gtest.h>

#include <vector>

#include "glide.h"
#include "motion_rig.h"

using namespace mega;

namespace {

struct GlideRunTest : ::testing::Test {
  Config config;  // 80 steps/mm, 100 mm/s; Y 1500 mm/s²: 120000 steps/s²
  MotionRig rig{config};
  // The intervals the glide should run, from its plan.
  std::vector<uint16_t> planned(uint32_t steps) {
    const AxisLimits y = rig.motion.limits(1, 0);
    uv::GlidePlan p;
    EXPECT_TRUE(uv::planGlide(steps, y.rate, y.accel, p));
    std::vector<uint16_t> out;
    uv::Glide g{p.first, static_cast<uint8_t>(steps), static_cast<uint8_t>(steps)};
    for (;;) {
      out.push_back(g.interval);
      if (--g.left == 0) return out;
      g.interval = uv::glideNext(g);
    }
  }
  std::vector<StepEvent> axisSteps(uint8_t bit) const {
    std::vector<StepEvent> out;
    for (const StepEvent& e : rig.steps)
      if (e.axes & bit) out.push_back(e);
    return out;
  }
};

}  // namespace

TEST_F(GlideRunTest, AGlideAloneStepsAtItsPlannedIntervals) {
  ASSERT_TRUE(rig.motion.glides(16));
  ASSERT_TRUE(rig.motion.glide(16));
  EXPECT_FALSE(rig.motion.idle());
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(1), 16);
  EXPECT_EQ(rig.head[1], 16);
  const std::vector<StepEvent> y = axisSteps(2);
  const std::vector<uint16_t> c = planned(16);
  ASSERT_EQ(y.size(), 16u);
  for (size_t i = 1; i < y.size(); i++) EXPECT_EQ(y[i].us2 - y[i - 1].us2, c[i]) << "step " << i;
  // And back, towards −Y.
  rig.steps.clear();
  ASSERT_TRUE(rig.motion.glide(-16));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(1), 0);
  EXPECT_EQ(rig.head[1], 0);
}

TEST_F(GlideRunTest, AGlideBesideAStrokesRunOutLeavesEveryXStepWhereItWas) {
  const uint32_t ramp = rig.motion.strokeRampSteps(1000, 0);  // 25 mm/s
  const int32_t n = static_cast<int32_t>(2 * ramp + 200);
  // The stroke alone.
  ASSERT_TRUE(rig.motion.stroke({n, 1000, 0, ramp + 1}));
  const uint64_t t0 = rig.now;
  ASSERT_TRUE(rig.runIdle());
  std::vector<uint64_t> alone;
  for (const StepEvent& e : axisSteps(1)) alone.push_back(e.us2 - t0);
  // Again from the same place with a fresh engine, a hop of 16 steps gliding from the first step of
  // its run-out.
  MotionRig again{config};
  ASSERT_TRUE(again.motion.stroke({n, 1000, 0, ramp + 1}));
  const uint64_t t1 = again.now;
  ASSERT_TRUE(again.runUntil([&] { return again.pos(0) >= n - static_cast<int32_t>(ramp); }, 10000000));
  EXPECT_FALSE(again.motion.glide(0));
  ASSERT_TRUE(again.motion.glide(16));
  EXPECT_FALSE(again.motion.moveToSteps(std::vector<int32_t>{n, 20, 0}.data())) << "a move in Y waits for the glide";
  ASSERT_TRUE(again.motion.moveToSteps(std::vector<int32_t>{n + 10, 16, 0}.data())) << "X alone goes beside it";
  ASSERT_TRUE(again.runIdle());
  EXPECT_EQ(again.pos(0), n + 10);
  EXPECT_EQ(again.pos(1), 16);
  EXPECT_EQ(again.head[1], 16);
  std::vector<uint64_t> beside;
  uint32_t yBeside = 0;
  for (const StepEvent& e : again.steps) {
    if (e.axes & 1) beside.push_back(e.us2 - t1);
    if ((e.axes & 2) && beside.size() < static_cast<size_t>(n)) yBeside++;
  }
  ASSERT_GE(beside.size(), alone.size());
  for (size_t i = 0; i < alone.size(); i++) ASSERT_EQ(beside[i], alone[i]) << "X step " << i;
  EXPECT_GE(yBeside, 3u) << "the hop stepped while X still ran out (12.5 ms: its first four steps take 8.2 ms)";
  EXPECT_EQ(again.engine.underruns(), 0);
}

TEST_F(GlideRunTest, AHaltEndsAGlide) {
  ASSERT_TRUE(rig.motion.glide(200));
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(1) >= 20; }, 10000000));
  rig.motion.halt();
  EXPECT_FALSE(rig.engine.gliding());
  ASSERT_TRUE(rig.runIdle());
  EXPECT_LT(rig.pos(1), 200);
  EXPECT_TRUE(rig.motion.glide(-rig.pos(1)));  // and a new one may start
}

TEST_F(GlideRunTest, WhatCannotGlideIsRefused) {
  EXPECT_FALSE(rig.motion.glides(0));
  EXPECT_FALSE(rig.motion.glides(256));
  EXPECT_TRUE(rig.motion.glides(-255));
  const int32_t to[3] = {0, 100, 0};
  ASSERT_TRUE(rig.motion.moveToSteps(to));
  EXPECT_FALSE(rig.motion.glide(16)) << "a queued move moves Y";
  ASSERT_TRUE(rig.runIdle());
  EXPECT_TRUE(rig.motion.glide(16));
  EXPECT_FALSE(rig.motion.glide(16)) << "one glide at a time";
}
