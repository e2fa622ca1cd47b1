// A pass's stroke run through the step interrupt's code: the head crosses the start mark, and
// every window edge after it, at the Nano's time (G step + kMarkLeadUs + shift) to within a tick.
#include <gtest/gtest.h>

#include <cmath>

#include "motion_rig.h"
#include "scan_stroke.h"

using namespace mega;

namespace {

struct Case {
  uint32_t windowUs, pitchUm, stepsMilli;
  int32_t firstX, lastX;  // bed µm of window 0's column and the last's
  bool descending;
};

// The head's X in steps at tick t, from the step events: linear between one step and the next.
double headAt(const std::vector<StepEvent>& ev, int32_t start, int sign, double t) {
  for (size_t i = 1; i < ev.size(); i++)
    if (ev[i].us2 >= t) return start + sign * (i + (t - ev[i - 1].us2) / static_cast<double>(ev[i].us2 - ev[i - 1].us2));
  return NAN;
}

}  // namespace

TEST(ScanStroke, TheHeadIsOnTheMarkAtThePlansTimeZero) {
  const Case cases[] = {
      {500, 50, 80000, 10000, 30000, false},   // 4 steps a window, 250 ticks a step
      {2000, 50, 80000, 40000, 5000, true},
      {1777, 42, 80000, 12345, 23456, false},  // 3.36 steps a window: fractional everything
      {3001, 25, 100000, 50000, 20000, true},
      {1640, 127, 157480, 3000, 90000, false},  // 20 steps a window
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.windowUs);
    Config config;
    ASSERT_TRUE(config.setHeld(Key::StepsX, static_cast<int32_t>(c.stepsMilli)));
    MotionRig rig{config};
    StrokeInput in{};
    const int32_t p = static_cast<int32_t>(c.pitchUm), dir = c.descending ? -1 : 1;
    in.markX2Um = 2 * c.firstX - dir * p;
    in.endX2Um = 2 * c.lastX + dir * p;
    in.descending = c.descending;
    in.windowUs = c.windowUs;
    in.pitchUm = c.pitchUm;
    in.stepsMilli = c.stepsMilli;
    uint16_t iv, fr;
    ASSERT_TRUE(strokeInterval(c.windowUs, c.pitchUm, c.stepsMilli, iv, fr));
    in.rampSteps = rig.motion.strokeRampSteps(iv, fr);
    StrokePlan s;
    ASSERT_TRUE(planStroke(in, s));
    ASSERT_GT(s.markStep, in.rampSteps);
    const int32_t home[3] = {s.startSteps, 0, 0};
    rig.motion.setPositionSteps(home);
    ASSERT_TRUE(rig.motion.stroke({s.steps, s.interval, s.frac, s.markStep}));
    ASSERT_TRUE(rig.runIdle());
    ASSERT_EQ(rig.marks.size(), 1u);
    EXPECT_EQ(rig.pos(0), s.startSteps + s.steps);
    // Time 0 on the Nano, in ticks; then window j's start edge is at time 0 + shift + j·W.
    const double zero = static_cast<double>(rig.marks[0]) + 2.0 * kMarkLeadUs;
    const double stepsPerUm = c.stepsMilli / 1e6;
    const uint32_t windows = static_cast<uint32_t>(std::abs(c.lastX - c.firstX) / p + 1);
    for (uint32_t j = 0; j <= windows; j += (j + 7 < windows ? 7 : 1)) {
      const double t = zero + 2.0 * (s.shiftUs + static_cast<double>(j) * c.windowUs);
      const double want = (in.markX2Um / 2.0 + dir * static_cast<double>(j) * p) * stepsPerUm;
      const double got = headAt(rig.steps, s.startSteps, dir, t);
      ASSERT_NEAR(got, want, 0.01) << "window " << j << " of " << windows;  // a hundredth of a step
    }
    // The windows are run at the speed: the ramps are over before the mark's lead and after the end.
    EXPECT_GE(static_cast<int64_t>(rig.marks[0]), static_cast<int64_t>(rig.steps[in.rampSteps].us2));
  }
}

TEST(ScanStroke, RefusesSpeedsTheStepEngineCannotRun) {
  uint16_t iv, fr;
  EXPECT_FALSE(strokeInterval(50, 50, 80000, iv, fr));         // 1000 mm/s: over kMaxStepRate
  EXPECT_FALSE(strokeInterval(4000000, 50, 80000, iv, fr));    // an interval over 16 bits
  EXPECT_FALSE(strokeInterval(2000, 0, 80000, iv, fr));
  EXPECT_TRUE(strokeInterval(2000, 50, 80000, iv, fr));
  EXPECT_EQ(iv, 1000);
  EXPECT_EQ(fr, 0);
}

TEST(ScanStroke, RefusesAStrokeWhoseMiddleOutrunsA32BitCountOfTicks) {
  // 1000 µs windows of 50 µm at 80 steps/mm: 500 ticks a step. 2³² ticks are 8589934 steps.
  StrokeInput in{};
  in.windowUs = 1000;
  in.pitchUm = 50;
  in.stepsMilli = 80000;
  in.rampSteps = 100;
  in.markX2Um = 0;
  StrokePlan s;
  in.endX2Um = 2 * 100000000;  // 100 m: 8000000 steps, 2000 s
  EXPECT_TRUE(planStroke(in, s));
  in.endX2Um = 2 * 110000000;  // 110 m: 8800000 steps, 2200 s
  EXPECT_FALSE(planStroke(in, s));
  EXPECT_LT(kScanLongestPassUs, (1ull << 31) - 1000000);  // M29's limit, with a second in hand
}
