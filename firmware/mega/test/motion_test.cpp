// Motion maths: trapezoids in steps, Bresenham over three axes, stops, seeks and a late main loop,
// run through the step engine's interrupt code in simulated time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "job_plan.h"
#include "printhead_link.h"
#include "motion_rig.h"
#include "scan.h"
#include "scan_stroke.h"
#include "time_model.h"

using namespace mega;

namespace {

// Rates between consecutive steps of one axis, steps/s, with their times.
struct RatePoint {
  double t, rate;
};
std::vector<RatePoint> rates(const std::vector<StepEvent>& ev, uint8_t axis) {
  std::vector<RatePoint> out;
  uint64_t prev = 0;
  bool first = true;
  for (const StepEvent& e : ev) {
    if (!(e.axes & (1 << axis))) continue;
    if (!first) out.push_back({e.us2 / 2e6, 2e6 / static_cast<double>(e.us2 - prev)});
    prev = e.us2;
    first = false;
  }
  return out;
}

// Acceleration as the axis sees it: over every 10 ms the rate may change by accel × dt, plus one
// segment's step (rates are constant within a 2.5 ms segment and step at its edges).
void expectAccelWithin(const std::vector<RatePoint>& rs, double accel) {
  size_t j = 0;
  for (size_t i = 0; i < rs.size(); i++) {
    while (j < rs.size() && rs[j].t - rs[i].t < 0.010) j++;
    if (j == rs.size()) break;
    double dv = std::fabs(rs[j].rate - rs[i].rate), dt = rs[j].t - rs[i].t;
    ASSERT_LE(dv, accel * dt * 1.1 + accel * kSegmentUs / 1e6 + 50) << "at " << rs[i].t << " s";
  }
}

// From the first step to the end of the last step's interval: the move's time.
double moveSeconds(const std::vector<StepEvent>& ev) {
  return ev.empty() ? 0 : (ev.back().us2 + ev.back().interval - ev.front().us2) / 2e6;
}

}  // namespace

TEST(StepProfile, IsqrtIsExactlyTheFloor) {
  for (uint32_t n : {0u, 1u, 2u, 3u, 4u, 15u, 16u, 17u, 99u, 100u, 65535u, 65536u, 400000000u, 1073741823u, 4294967295u}) {
    uint32_t r = uv::isqrt32(n);
    EXPECT_LE(static_cast<uint64_t>(r) * r, n);
    EXPECT_GT(static_cast<uint64_t>(r + 1) * (r + 1), n);
  }
}

TEST(StepProfile, EveryAxisKeepsWithinItsOwnLimits) {
  AxisLimits lim[3] = {{8000, 160000}, {8000, 120000}, {4000, 80000}};
  uint32_t steps[3] = {8000, 4000, 100};
  Profile p = profileFor(steps, lim);
  EXPECT_EQ(p.total, 8000u);
  EXPECT_EQ(p.rate, 8000u);
  EXPECT_EQ(p.accel, 160000u);  // Y at half the steps may take twice its 120000: X limits
  uint32_t steep[3] = {1000, 8000, 0};
  p = profileFor(steep, lim);
  EXPECT_EQ(p.accel, 120000u);
  EXPECT_EQ(p.rampSteps, (8000u * 8000u + 240000u - 1) / 240000u);
  uint32_t fast[3] = {8000, 0, 0};
  AxisLimits quick[3] = {{90000, 160000}, {1, 1}, {1, 1}};
  EXPECT_EQ(profileFor(fast, quick).rate, kMaxStepRate);
}

TEST(StepProfile, SegmentsAddUpToTheMoveAndNeverExceedTheRate) {
  AxisLimits lim[3] = {{8000, 160000}, {8000, 160000}, {4000, 80000}};
  for (uint32_t n : {1u, 2u, 3u, 10u, 77u, 400u, 8000u, 123457u}) {
    uint32_t steps[3] = {n, 0, 0};
    Profile p = profileFor(steps, lim);
    uint32_t done = 0, segments = 0;
    while (done < n) {
      Segment s = nextSegment(p, done);
      ASSERT_GE(s.steps, 1);
      ASSERT_GE(s.interval, kTickHz / p.rate);
      done += s.steps;
      segments++;
    }
    EXPECT_EQ(done, n);
    EXPECT_EQ(nextSegment(p, n).steps, 0);
  }
}

class MotionTest : public ::testing::Test {
 protected:
  Config config;
  MotionRig rig{config};
};

TEST_F(MotionTest, AOneAxisMoveTakesThePlannersTimeWithinItsAcceleration) {
  // 100 mm/s, 2000 mm/s², 80 steps/mm: the planner's time model is what jobs are estimated with.
  for (int32_t d : {50, 1000, 5000, 20000, 150000}) {
    MotionRig r{config};
    int32_t to[3] = {d, 0, 0};
    ASSERT_TRUE(r.motion.moveTo(to, 0));
    ASSERT_TRUE(r.runIdle());
    EXPECT_EQ(r.pos(0), d * 80 / 1000);
    double expected = uv::moveTimeUs(static_cast<uint32_t>(d), 100000, 2000000) / 1e6;
    double took = moveSeconds(r.steps);
    SCOPED_TRACE(d);
    EXPECT_NEAR(took, expected, expected * 0.03 + 0.004);
    std::vector<RatePoint> rs = rates(r.steps, 0);
    for (const RatePoint& p : rs) ASSERT_LE(p.rate, 8000 * 1.001);
    expectAccelWithin(rs, 160000);
  }
}

TEST_F(MotionTest, DiagonalMovesEndExactlyAndKeepEachAxisInItsLimits) {
  std::mt19937 rng(3);
  int32_t here[3] = {0, 0, 0};
  for (int i = 0; i < 30; i++) {
    rig.steps.clear();
    int32_t to[3] = {static_cast<int32_t>(rng() % 200000), static_cast<int32_t>(rng() % 200000), static_cast<int32_t>(rng() % 40000)};
    ASSERT_TRUE(rig.motion.moveTo(to, 0));
    ASSERT_TRUE(rig.runIdle());
    for (uint8_t a = 0; a < 3; a++) EXPECT_EQ(rig.pos(a), rig.motion.toSteps(a, to[a]));
    // Never faster than the slowest axis's own trapezoid (the planner's estimate), rarely much slower.
    uint32_t v[3] = {100000, 100000, 10000}, acc[3] = {2000000, 1500000, 200000};
    double bound = 0;
    for (uint8_t a = 0; a < 3; a++) {
      uint32_t d = static_cast<uint32_t>(std::abs(to[a] - here[a]));
      bound = std::max(bound, uv::moveTimeUs(d, v[a], acc[a]) / 1e6);
    }
    double took = moveSeconds(rig.steps);
    EXPECT_GE(took, bound * 0.97 - 0.004);
    EXPECT_LE(took, bound * 1.35 + 0.004);
    std::copy(to, to + 3, here);
  }
  EXPECT_EQ(rig.engine.underruns(), 0);
}

TEST_F(MotionTest, EightMovesQueueAndTheNinthWaits) {
  for (int i = 0; i < 8; i++) {
    int32_t to[3] = {(i + 1) * 1000, 0, 0};
    EXPECT_EQ(rig.motion.movesFree(), 8 - i);
    ASSERT_TRUE(rig.motion.moveTo(to, 0));
  }
  int32_t ninth[3] = {0, 0, 0};
  EXPECT_FALSE(rig.motion.moveTo(ninth, 0));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(0), 8 * 80);
  EXPECT_TRUE(rig.motion.moveTo(ninth, 0));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(0), 0);
}

TEST_F(MotionTest, AStopDeceleratesDropsTheQueueAndTheNextMoveStartsWhereItStopped) {
  int32_t far[3] = {150000, 0, 0}, back[3] = {0, 0, 0};
  ASSERT_TRUE(rig.motion.moveTo(far, 0));
  ASSERT_TRUE(rig.motion.moveTo(back, 0));
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(0) >= 6000; }, 5000000));  // cruising at 75 mm
  double vAtStop = rates(rig.steps, 0).back().rate;
  rig.motion.stop();
  EXPECT_EQ(rig.motion.movesFree(), 0);  // nothing is taken while it runs down
  ASSERT_TRUE(rig.runIdle());
  int32_t stoppedAt = rig.pos(0);
  // v² / 2a = 8000² / 320000 = 200 steps, plus what was queued (at most 40 ms at 8000 steps/s).
  EXPECT_GE(stoppedAt, 6000 + 150);
  EXPECT_LE(stoppedAt, 6000 + 200 + 320 + 10);
  std::vector<RatePoint> rs = rates(rig.steps, 0);
  expectAccelWithin(rs, 160000);
  EXPECT_NEAR(vAtStop, 8000, 10);
  EXPECT_LT(rs.back().rate, 1000);  // came to rest, not cut off
  int32_t target[3];
  rig.motion.targetUm(target);
  EXPECT_EQ(rig.motion.toSteps(0, target[0]), stoppedAt);
  int32_t plus[3] = {target[0] + 1000, 0, 0};
  ASSERT_TRUE(rig.motion.moveTo(plus, 0));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.pos(0), stoppedAt + 80);
}

TEST_F(MotionTest, AStopDuringAccelerationOrBetweenMovesEndsAtRest) {
  for (int32_t at : {3, 40, 250}) {
    MotionRig r{config};
    int32_t far[3] = {150000, 150000, 0};
    ASSERT_TRUE(r.motion.moveTo(far, 0));
    ASSERT_TRUE(r.runUntil([&] { return r.pos(0) >= at; }, 5000000));
    r.motion.stop();
    ASSERT_TRUE(r.runIdle());
    EXPECT_LT(r.pos(0), at + 700);
    EXPECT_EQ(r.pos(0), r.pos(1));  // still on the diagonal
  }
  MotionRig idle{config};
  idle.motion.stop();
  ASSERT_TRUE(idle.runIdle());
  EXPECT_EQ(idle.pos(0), 0);
}

TEST_F(MotionTest, AHaltStopsAtOnce) {
  int32_t far[3] = {150000, 0, 0};
  ASSERT_TRUE(rig.motion.moveTo(far, 0));
  ASSERT_TRUE(rig.runUntil([&] { return rig.pos(0) >= 6000; }, 5000000));
  rig.motion.halt();
  size_t before = rig.steps.size();
  ASSERT_TRUE(rig.runIdle());
  EXPECT_LE(rig.steps.size() - before, 1u);
  EXPECT_TRUE(rig.motion.accepting());
}

TEST_F(MotionTest, ASeekEndsExactlyWhereTheSwitchClosesAndIgnoresABounce) {
  int32_t start[3] = {4000, 0, 0};
  rig.motion.setPositionSteps(start);
  rig.head[0] = 4000;  // and the head is physically there: 4000 steps above its switch
  rig.switchAt[0] = 0;
  ASSERT_TRUE(rig.motion.seek(0, -5000, 800));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_TRUE(rig.engine.seekHit());
  EXPECT_EQ(rig.pos(0), 0);  // closed at 0, confirmed by a second reading an interval later
  EXPECT_EQ(rig.engine.seekSteps(), 4000u);
  // A single closed reading (a bounce, noise on the wire) does not end a seek.
  int32_t again[3] = {4000, 0, 0};
  rig.motion.setPositionSteps(again);
  rig.head[0] = 4000;
  rig.switchAt[0] = INT32_MIN;
  int readings = 0;
  rig.endstopOverride = [&](uint8_t bits) { return ++readings == 100 ? static_cast<uint8_t>(bits | 1) : bits; };
  ASSERT_TRUE(rig.motion.seek(0, -1000, 800));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_FALSE(rig.engine.seekHit());
  EXPECT_EQ(rig.pos(0), 3000);
  rig.endstopOverride = nullptr;
  // A seek that never meets its switch runs its whole length and says so.
  rig.switchAt[0] = -100000;
  ASSERT_TRUE(rig.motion.seek(0, -300, 800));
  ASSERT_TRUE(rig.runIdle());
  EXPECT_FALSE(rig.engine.seekHit());
  EXPECT_EQ(rig.pos(0), 2700);
}

TEST_F(MotionTest, AMainLoopUpTo30msLateNeverStarvesTheStepInterrupt) {
  std::mt19937 rng(11);
  rig.loopJitter = [&] { return rng() % 4 == 0 ? static_cast<uint32_t>(rng() % 60000) : 0u; };  // up to 30 ms
  for (int i = 0; i < 20; i++) {
    int32_t to[3] = {static_cast<int32_t>(rng() % 200000), static_cast<int32_t>(rng() % 200000), 0};
    while (!rig.motion.moveTo(to, 0)) ASSERT_TRUE(rig.runUntil([&] { return rig.motion.accepting(); }, 10000000));
  }
  ASSERT_TRUE(rig.runIdle());
  EXPECT_EQ(rig.engine.underruns(), 0);
  // The counter does see it when the loop is later than the 40 ms the segments cover.
  MotionRig late{config};
  late.loopJitter = [&] { return rng() % 4 == 0 ? 160000u : 0u; };  // 80 ms
  int32_t far[3] = {150000, 150000, 0};
  ASSERT_TRUE(late.motion.moveTo(far, 0));
  ASSERT_TRUE(late.runIdle());
  EXPECT_GT(late.engine.underruns(), 0);
}

// The planner's time model (planner.md "Time model", "The stroke") prices moves as this step engine
// runs them: to the half µs, for moves on X, Y and both, short hops and long ones.
TEST_F(MotionTest, ThePlannersStepEngineTimesEveryMoveAsTheEngineRunsIt) {
  const uv::MotionModel m = plannerMachine(config, 0, 0, kJobLinkBaud);
  std::mt19937 rng(5);
  for (int i = 0; i < 60; i++) {
    MotionRig r{config};
    const int32_t scale = i % 3 == 0 ? 300 : i % 3 == 1 ? 5000 : 200000;
    int32_t to[3] = {static_cast<int32_t>(rng() % scale), static_cast<int32_t>(i % 4 == 0 ? 0 : rng() % scale), 0};
    if (i == 0) {  // the 4-step hop between stops at 50 µm
      to[0] = 50;
      to[1] = 0;
    }
    ASSERT_TRUE(r.motion.moveTo(to, 0));
    ASSERT_TRUE(r.runIdle());
    SCOPED_TRACE(testing::Message() << to[0] << ", " << to[1]);
    EXPECT_NEAR(moveSeconds(r.steps) * 1e6, uv::engineMoveUs(m, 0, 0, to[0], to[1]), 0.5);
    if (i == 0) {
      EXPECT_EQ(uv::engineMoveUs(m, 0, 0, to[0], to[1]), 7890u);  // 2.5 + 1.445 + 1.445 + 2.5 ms
    }
  }
}

TEST_F(MotionTest, ThePlannersStrokeIsTheOneTheMegaRunsAndTakesItsTime) {
  const uv::MotionModel m = plannerMachine(config, 0, 0, kJobLinkBaud);
  for (uint32_t window : {2000u, 4000u, 25000u, 100000u, 130000u}) {
    for (bool descending : {false, true}) {
      SCOPED_TRACE(testing::Message() << window << (descending ? " −X" : " +X"));
      MotionRig r{config};
      // A pass of 24 windows at 50 µm from X 20 mm: the mark half a pitch before window 0's column.
      const int32_t firstX = descending ? 21150 : 20000, lastX = descending ? 20000 : 21150, dir = descending ? -1 : 1;
      StrokeInput in{2 * firstX - dir * 50, 2 * lastX + dir * 50, descending, window, 50, r.motion.stepsMilli(0), 0};
      uint16_t interval, frac;
      ASSERT_TRUE(strokeInterval(window, 50, in.stepsMilli, interval, frac));
      in.rampSteps = r.motion.strokeRampSteps(interval, frac);
      StrokePlan k;
      ASSERT_TRUE(planStroke(in, k));
      uint64_t q16;
      ASSERT_TRUE(uv::engineStep(m, 50, window, q16));
      uv::ScanPass pass{};
      uv::planStroke(m, in.markX2Um, in.endX2Um, descending, q16, 0, pass);
      EXPECT_EQ(pass.startSteps, k.startSteps);
      EXPECT_EQ(pass.stopSteps, k.startSteps + k.steps);
      const int32_t start[3] = {k.startSteps, 0, 0};
      ASSERT_TRUE(r.motion.moveToSteps(start));
      ASSERT_TRUE(r.runIdle());
      r.steps.clear();
      ASSERT_TRUE(r.motion.stroke({k.steps, k.interval, k.frac, k.markStep, nullptr, nullptr}));
      ASSERT_TRUE(r.runIdle());
      EXPECT_NEAR(moveSeconds(r.steps) * 1e6, pass.strokeUs, 1);
      // The mark: the G step, then the lead and the shift.
      ASSERT_EQ(r.marks.size(), 1u);
      EXPECT_NEAR((r.marks[0] - r.steps.front().us2) / 2.0 + kMarkLeadUs + k.shiftUs, pass.markUs, 1);
    }
  }
  uint64_t q16;
  EXPECT_FALSE(uv::engineStep(m, 50, 200000, q16));  // 50 ms a step: E29 at M29 (mega.md)
  EXPECT_TRUE(uv::engineStep(m, 50, 131000, q16));
}
