// A stroke's flown stretches (Motion::StrokeJump, jump_path.h): the path alone, then run through the
// step interrupt's code: every step after a stretch falls where the speed puts it less what the
// stretches saved, the speed changes no faster than the axis's acceleration, and a stop in the middle
// of one slows down from the speed the head has.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "jump_path.h"
#include "motion_rig.h"

using namespace mega;

namespace {

constexpr float kTicks = 2000000.0f;
// 80 steps/mm, 2000 mm/s²: 160000 steps/s² in steps per tick².
constexpr float kAccel = 160000.0f / (kTicks * kTicks);
// The step interrupt runs segments of one rate each, about kSegmentUs long: from one to the next the
// rate may change by what the acceleration gives over a segment (and half as much again for the
// segments cut short at a stretch's ends).
constexpr double kSegmentStep = 160000.0 * kSegmentUs / 1e6 * 1.5;

TEST(JumpPath, StartsAndEndsAtTheSpeedInExactlyItsTime) {
  struct Case {
    uint32_t steps, ticks;
    float rate;  // steps per tick
  } cases[] = {
      {400, 170000, 1.0f / 1000},  // 2000 steps/s over 400 steps (200000 ticks at the speed): a triangle
      {4000, 1200000, 1.0f / 1000},  // long: a cruise in the middle
      {24, 21000, 1.0f / 1000},    // short and a hair faster than the acceleration allows
  };
  for (const Case& c : cases) {
    JumpPath p;
    p.plan(c.steps, c.ticks, c.rate, kAccel);
    EXPECT_EQ(p.at(0), 0.0f);
    EXPECT_EQ(p.at(c.steps), static_cast<float>(c.ticks));
    float last = 0, lastDt = 1 / c.rate;
    for (uint32_t x = 1; x <= c.steps; x++) {
      const float t = p.at(x), dt = t - last;
      ASSERT_GT(dt, 0) << x;
      // Each step's speed against the one before: the change is the path's acceleration over it.
      const float dv = std::fabs(1 / dt - 1 / lastDt), bound = p.accel() * (dt + lastDt) * 0.6f + 1e-7f;
      ASSERT_LE(dv, bound) << "step " << x << " of " << c.steps;
      last = t;
      lastDt = dt;
    }
    // Back at the speed at the end, as it left it.
    EXPECT_NEAR(1 / (p.at(1) - p.at(0)), c.rate, c.rate * 0.1f);
    EXPECT_NEAR(1 / (p.at(c.steps) - p.at(c.steps - 1)), c.rate, c.rate * 0.1f);
    EXPECT_LE(p.accel(), kAccel * 1.05f);
  }
}

struct Flown {
  std::vector<Motion::StrokeJump> jumps;
  static bool at(void* ctx, uint8_t i, Motion::StrokeJump& out) {
    const Flown* f = static_cast<Flown*>(ctx);
    if (i >= f->jumps.size()) return false;
    out = f->jumps[i];
    return true;
  }
};

struct StrokeJumpTest : ::testing::Test {
  Config config;  // 80 steps/mm, 2000 mm/s², 100 mm/s
  MotionRig rig{config};
};

}  // namespace

TEST_F(StrokeJumpTest, EveryStepAfterAStretchIsWhereTheSpeedPutsItLessWhatWasSaved) {
  const uint16_t interval = 1000, frac = static_cast<uint16_t>(0.37 * 65536);  // 1000.37 ticks a step
  const double exact = interval + frac / 65536.0;
  const uint32_t ramp = rig.motion.strokeRampSteps(interval, frac);
  const uint32_t total = 2 * ramp + 6000, mark = ramp + 100;
  // Three stretches; what each saves is what flying them in a triangle or trapezoid at the axis's
  // acceleration would, less a margin (the planner's F(g) has room for it).
  Flown f;
  const uint32_t at[3][2] = {{ramp + 500, 400}, {ramp + 1500, 2400}, {ramp + 4500, 60}};
  for (const auto& a : at) {
    const double v = 2000, acc = 160000, vmax = 8000, d = a[1];
    // Fastest from v back to v over d steps: up to vmax and down, or a triangle.
    const double dUp = (vmax * vmax - v * v) / acc;
    const double t = d >= dUp ? 2 * (vmax - v) / acc + (d - dUp) / vmax : 2 * (std::sqrt(v * v + acc * d) - v) / acc;
    const uint32_t saved = static_cast<uint32_t>((d / v - t) * 0.95 * kTicks);
    f.jumps.push_back({a[0], a[1], saved});
  }
  ASSERT_TRUE(rig.motion.stroke({static_cast<int32_t>(total), interval, frac, mark, &Flown::at, &f}));
  ASSERT_TRUE(rig.runIdle());
  ASSERT_EQ(rig.steps.size(), total);
  EXPECT_EQ(rig.pos(0), static_cast<int32_t>(total));
  EXPECT_EQ(rig.engine.underruns(), 0);
  const uint64_t t0 = rig.steps[ramp].us2;
  double saved = 0;
  size_t next = 0;
  uint32_t fastest = 0xffff;
  for (uint32_t i = ramp; i < total - ramp; i++) {
    if (next < f.jumps.size() && i == f.jumps[next].from + f.jumps[next].steps) saved += f.jumps[next++].savedTicks;
    const bool inside = next < f.jumps.size() && i > f.jumps[next].from;
    if (!inside) {
      ASSERT_NEAR(static_cast<double>(rig.steps[i].us2 - t0), (i - ramp) * exact - saved, 1.0) << "step " << i;
    }
    const uint32_t dt = static_cast<uint32_t>(rig.steps[i].us2 - rig.steps[i - 1].us2);
    if (dt < fastest) fastest = dt;
    const double prev = static_cast<double>(rig.steps[i - 1].us2 - rig.steps[i - 2].us2);
    ASSERT_LE(std::fabs(kTicks / dt - kTicks / prev), kSegmentStep) << "step " << i;
  }
  EXPECT_EQ(next, f.jumps.size());
  EXPECT_LT(fastest, 400u);  // the long stretch went well past the speed (1000 ticks a step)
  EXPECT_GE(fastest, 250u);  // and not past the axis's 8000 steps/s
}

TEST_F(StrokeJumpTest, AStopInAStretchSlowsDownFromTheSpeedTheHeadHas) {
  const uint32_t ramp = rig.motion.strokeRampSteps(1000, 0);
  Flown f;
  f.jumps.push_back({ramp + 200, 8000, 2 * 2000000});  // 8000 steps, 4 s at the speed, flown in 2 at up to 4013 steps/s
  ASSERT_TRUE(rig.motion.stroke({static_cast<int32_t>(2 * ramp + 10000), 1000, 0, 0, &Flown::at, &f}));
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(0) > static_cast<int32_t>(ramp + 3000); }, 10000000));
  const size_t cut = rig.steps.size();
  const uint32_t before = static_cast<uint32_t>(rig.steps[cut - 1].us2 - rig.steps[cut - 2].us2);
  ASSERT_LT(before, 600u);  // flying: about 500 ticks a step, half the speed's
  rig.motion.stop();
  ASSERT_TRUE(rig.runIdle());
  EXPECT_LT(rig.pos(0), static_cast<int32_t>(2 * ramp + 10000));
  for (size_t i = cut; i < rig.steps.size(); i++) {
    const double dt = static_cast<double>(rig.steps[i].us2 - rig.steps[i - 1].us2), prev = static_cast<double>(rig.steps[i - 1].us2 - rig.steps[i - 2].us2);
    ASSERT_LE(std::fabs(kTicks / dt - kTicks / prev), kSegmentStep) << "step " << i;
  }
  EXPECT_TRUE(rig.motion.stroke({-100, 1000, 0, 0}));  // nothing of it is left
}

TEST_F(StrokeJumpTest, StretchesThatCannotBeFlownAreCrossedAtTheSpeed) {
  const uint32_t ramp = rig.motion.strokeRampSteps(1000, 0), total = 2 * ramp + 3000;
  Flown f;
  f.jumps.push_back({ramp + 100, 0, 1000});              // no steps
  f.jumps.push_back({ramp + 1000, 200, 200 * 1000});     // would save all its time
  f.jumps.push_back({ramp + 500, 100, 1000});            // behind the one before it
  f.jumps.push_back({total - ramp - 50, 100, 1000});     // past the middle's end
  ASSERT_TRUE(rig.motion.stroke({static_cast<int32_t>(total), 1000, 0, 0, &Flown::at, &f}));
  ASSERT_TRUE(rig.runIdle());
  ASSERT_EQ(rig.steps.size(), total);
  for (uint32_t i = ramp + 1; i < total - ramp; i++) ASSERT_EQ(rig.steps[i].us2 - rig.steps[i - 1].us2, 1000u) << "step " << i;
}
