#include "nano_clock.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mega;

TEST(NanoClock, OneExchangeSaysNothingAndTwoOverTwoSecondsGiveTheRate) {
  NanoClock c;
  c.sample(5000000, 123);
  EXPECT_FALSE(c.known());
  c.sample(6900000, 123 + 1900950);  // under the baseline: not trusted yet
  EXPECT_FALSE(c.known());
  c.sample(7000000, 123 + 2001000);  // 2 s by the Mega, 2.001 s by the Nano
  ASSERT_TRUE(c.known());
  EXPECT_EQ(c.ppm(), 500);
}

TEST(NanoClock, ASlowNanoAndClocksThatWrap) {
  NanoClock c;
  c.sample(4294000000u, 4294900000u);
  c.sample(4294000000u + 3000000, 4294900000u + 2985000);  // both past 2³² µs
  ASSERT_TRUE(c.known());
  EXPECT_EQ(c.ppm(), -5000);
}

TEST(NanoClock, ARateNoCrystalGivesStartsOverAndForgetDropsTheRate) {
  NanoClock c;
  c.sample(0, 0);
  c.sample(2000000, 2000100);
  ASSERT_TRUE(c.known());
  c.sample(4000000, 1500);  // the Nano restarted: its micros() began again
  EXPECT_FALSE(c.known());
  c.sample(6000000, 1500 + 2000000);  // measured again from the restart
  ASSERT_TRUE(c.known());
  EXPECT_EQ(c.ppm(), 0);
  c.forget();
  EXPECT_FALSE(c.known());
  c.sample(7000000, 9);
  EXPECT_FALSE(c.known());
}

TEST(NanoClock, TheRateFollowsADriftingClockOnceTheFirstExchangeIsOld) {
  NanoClock c;
  c.sample(0, 0);
  c.sample(kClockRebaseUs + 1000000, kClockRebaseUs + 1000000 + 301);  // 1 ppm: the anchor moves here
  EXPECT_EQ(c.ppm(), 1);
  c.sample(kClockRebaseUs + 3000000, kClockRebaseUs + 1000000 + 301 + 2000040);  // 20 ppm over the 2 s since then
  EXPECT_EQ(c.ppm(), 20);
}

TEST(NanoClock, MegaTimeAsTheNanoCountsItRoundsAndNeverWraps) {
  EXPECT_EQ(NanoClock::toNano(1600000, NanoClock::rate(0)), 1600000u);
  EXPECT_EQ(NanoClock::toNano(1600000, NanoClock::rate(5000)), 1608000u);
  EXPECT_EQ(NanoClock::toNano(1600000, NanoClock::rate(-5000)), 1592000u);
  EXPECT_EQ(NanoClock::toNano(999, NanoClock::rate(500)), 999u);    // 999.4995
  EXPECT_EQ(NanoClock::toNano(1001, NanoClock::rate(500)), 1002u);  // 1001.5005
  EXPECT_EQ(NanoClock::toNano(4000000000u, NanoClock::rate(-20000)), 3920000000u);
}

// The rate as a factor in 2⁻³² (no division an event): within a µs of the exact product, at any time
// and any rate a clock may have.
TEST(NanoClock, MegaTimeAsTheNanoCountsItIsWithinAMicrosecondOfExact) {
  uint32_t x = 0x39u;
  auto draw = [&x]() {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
  };
  for (int i = 0; i < 200000; i++) {
    const uint32_t us = i < 1000 ? static_cast<uint32_t>(i) : (i % 3 ? draw() : draw() % 4000000);
    const int32_t ppm = static_cast<int32_t>(draw() % (2 * kClockMaxPpm + 1)) - kClockMaxPpm;
    const double exact = us * (1.0 + ppm / 1e6);
    if (exact >= 4294967295.0) continue;  // past 2³² µs (71 minutes): no pass is that long
    const uint32_t nano = NanoClock::toNano(us, NanoClock::rate(ppm));
    ASSERT_LE(std::fabs(nano - exact), 1.0) << us << " µs at " << ppm << " ppm";
  }
}
