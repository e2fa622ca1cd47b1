// Host tests of the Timer1 compare wake rule that keeps the pixel write clear of switch-offs.
#include "compare_wake.h"

#include <gtest/gtest.h>

using nano::compareQuietFor;

TEST(CompareWake, QuietWhenNotArmedOrWrapsAway) {
  EXPECT_TRUE(compareQuietFor(false, 0, true, 100, 100, 1000));
  EXPECT_TRUE(compareQuietFor(true, 2, true, 100, 100, 1000));
  EXPECT_TRUE(compareQuietFor(true, 1, false, 100, 99, 1000));  // this match only counts a wrap
}

TEST(CompareWake, APendingMatchIsNeverQuiet) {
  // The counter has just passed OCR: without the flag, OCR - TCNT reads as almost a whole wrap.
  EXPECT_FALSE(compareQuietFor(true, 0, true, 100, 101, 1000));
  EXPECT_FALSE(compareQuietFor(true, 1, true, 100, 101, 1000));  // the last wrap is going now
}

TEST(CompareWake, DistanceToTheWakeCounts) {
  EXPECT_TRUE(compareQuietFor(true, 0, false, 5000, 3000, 1000));
  EXPECT_FALSE(compareQuietFor(true, 0, false, 3500, 3000, 1000));
  EXPECT_FALSE(compareQuietFor(true, 0, false, 10, 65500, 1000));  // across the counter's wrap: 46 ticks
}
