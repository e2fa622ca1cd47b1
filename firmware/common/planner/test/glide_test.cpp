// The Y hop's glide (glide.h): the intervals the step interrupt runs, against constant acceleration.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "glide.h"

namespace {

constexpr double kTickHz = 2000000;

std::vector<uint16_t> intervals(uint32_t steps, uint32_t rate, uint32_t accel) {
  uv::GlidePlan p;
  std::vector<uint16_t> out;
  if (!uv::planGlide(steps, rate, accel, p)) return out;
  uv::Glide g{p.first, static_cast<uint8_t>(steps), static_cast<uint8_t>(steps)};
  for (;;) {
    out.push_back(g.interval);
    if (--g.left == 0) return out;
    g.interval = uv::glideNext(g);
  }
}

}  // namespace

// Step by step, the speed (a step over its interval) changes by no more than the axis's acceleration
// allows over the time between the two intervals' middles, speeding up and slowing down; and the
// first step comes no sooner than constant acceleration from rest would take it.
TEST(Glide, NoStepSpeedsUpOrSlowsDownHarderThanTheAxisAllows) {
  double worstUp = 0, worstDown = 0;
  for (uint32_t accel : {7500u, 40000u, 120000u, 160000u, 400000u, 1000000u})
    for (uint32_t steps = 1; steps <= 255; steps++) {
      const std::vector<uint16_t> c = intervals(steps, 16000, accel);
      if (c.empty()) continue;
      EXPECT_GE(c[0] / kTickHz, std::sqrt(2.0 / accel) - 1 / kTickHz) << steps << " steps at " << accel;
      for (size_t i = 1; i < c.size(); i++) {
        const double dv = kTickHz / c[i] - kTickHz / c[i - 1], dt = (c[i] + c[i - 1]) / 2.0 / kTickHz;
        const double a = dv / dt / accel;
        worstUp = std::max(worstUp, a);
        worstDown = std::max(worstDown, -a);
        // A tick's rounding moves a short interval's speed by a part in a few thousand.
        EXPECT_LE(std::fabs(a), 1.01) << steps << " steps at " << accel << ", interval " << i;
      }
    }
  std::printf("[glide] the hardest step: speeding up %.3f, slowing down %.3f of the axis's acceleration\n", worstUp, worstDown);
}

// The way down mirrors the way up within a few ticks, so the hop comes to rest as it set off, and the
// plan's ticks are the intervals the interrupt runs.
TEST(Glide, ComesDownAsItWentUpAndThePlanIsItsTicks) {
  for (uint32_t accel : {7500u, 120000u, 1000000u})
    for (uint32_t steps = 1; steps <= 255; steps++) {
      const std::vector<uint16_t> c = intervals(steps, 16000, accel);
      if (c.empty()) continue;
      uv::GlidePlan p;
      ASSERT_TRUE(uv::planGlide(steps, 16000, accel, p));
      uint32_t sum = 0;
      for (size_t i = 0; i < c.size(); i++) {
        sum += c[i];
        const double mirrored = c[c.size() - 1 - i];
        EXPECT_NEAR(c[i], mirrored, 0.01 * c[i] + 2) << steps << " steps at " << accel << ", interval " << i;
      }
      EXPECT_EQ(sum, p.ticks);
    }
}

// 16 steps at 120000 steps/s² (the bench's hop: four rows of 50 µm at 80 steps/mm, 1500 mm/s²):
// against the continuous triangle's 2√(d/a), 23.1 ms.
TEST(Glide, TheBenchHopTakesAboutTheTriangleItFollows) {
  uv::GlidePlan p;
  ASSERT_TRUE(uv::planGlide(16, 8000, 120000, p));
  const double ideal = 2 * std::sqrt(16 / 120000.0);
  std::printf("[glide] 16 steps at 120000 steps/s^2: %.2f ms, the continuous triangle %.2f ms\n", p.ticks / kTickHz * 1e3, ideal * 1e3);
  EXPECT_GT(p.ticks / kTickHz, ideal);
  EXPECT_LT(p.ticks / kTickHz, ideal * 1.02);
}

TEST(Glide, RefusesWhatItCannotRun) {
  uv::GlidePlan p;
  EXPECT_FALSE(uv::planGlide(0, 8000, 120000, p));
  EXPECT_FALSE(uv::planGlide(256, 8000, 120000, p));
  EXPECT_FALSE(uv::planGlide(16, 8000, 7400, p));      // a first interval over 15 bits
  EXPECT_TRUE(uv::planGlide(16, 8000, 7500, p));
  EXPECT_FALSE(uv::planGlide(200, 100, 120000, p));    // faster than the axis's top rate
  EXPECT_FALSE(uv::planGlide(255, 16000, 100000000, p));  // over 16000 steps/s
  EXPECT_FALSE(uv::planGlide(16, 0, 120000, p));
  EXPECT_FALSE(uv::planGlide(16, 8000, 0, p));
}
