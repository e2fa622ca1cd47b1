// The Mega's division-free quotients against the division they stand for.
#include "fast_div.h"

#include <gtest/gtest.h>

using namespace mega;

TEST(FastDiv, MillisecondsAreTheExactQuotientForEveryKindOfMicrosecondCount) {
  // Around every thousand up to 2³² in steps, the edges of the range, and a spread of others.
  for (uint64_t k = 0; k <= 4294967; k += 997) {
    for (int d = -2; d <= 2; d++) {
      const int64_t us = static_cast<int64_t>(k * 1000) + d;
      if (us < 0 || us > 0xFFFFFFFFll) continue;
      ASSERT_EQ(msOf(static_cast<uint32_t>(us)), static_cast<uint32_t>(us) / 1000u) << us;
    }
  }
  for (uint32_t us : {0u, 1u, 999u, 1000u, 4294966999u, 4294967000u, 4294967295u}) EXPECT_EQ(msOf(us), us / 1000u) << us;
  uint32_t x = 0x39u;
  for (int i = 0; i < 1000000; i++) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    ASSERT_EQ(msOf(x), x / 1000u) << x;
  }
}

TEST(FastDiv, TheHighHalfIsTheTopThirtyTwoBits) {
  EXPECT_EQ(highHalf(0x0123456789ABCDEFull), 0x01234567u);
  EXPECT_EQ(highHalf(0xFFFFFFFF00000000ull), 0xFFFFFFFFu);
  EXPECT_EQ(highHalf(0x00000000FFFFFFFFull), 0u);
}
