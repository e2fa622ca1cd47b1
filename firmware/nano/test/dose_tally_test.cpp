// Host tests of the dose tally: on-times per F and per scan program, split at program ends and cuts.
#include "dose_tally.h"

#include <gtest/gtest.h>

using namespace nano;

namespace {
uint32_t word(uint32_t d, uint8_t m) { return d << 4 | m; }

uv::NanoCommand fireCmd(uint8_t mask, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  uv::NanoCommand f{};
  f.op = 'F';
  f.mask = mask;
  f.durations[0] = a;
  f.durations[1] = b;
  f.durations[2] = c;
  f.durations[3] = d;
  return f;
}
}  // namespace

TEST(DoseTally, AWholeFIsEachLitLedsDuration) {
  DoseTally t;
  t.begin(7);
  t.openFire(fireCmd(0b1011, 250, 100, 999, 10000000));
  EXPECT_TRUE(t.fireOpen());
  EXPECT_EQ(t.waiting(), 0u);  // not before it has gone dark
  t.closeFire(DoseTally::kWhole);
  DoseRecord r;
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.exposure, 7u);
  EXPECT_EQ(r.program, 0u);
  EXPECT_EQ(r.onUs[0], 250u);
  EXPECT_EQ(r.onUs[1], 100u);
  EXPECT_EQ(r.onUs[2], 0u);  // not in the mask
  EXPECT_EQ(r.onUs[3], 10000000u);
  EXPECT_FALSE(t.take(r));
}

TEST(DoseTally, ACutFKeepsWhatRanBeforeTheCut) {
  DoseTally t;
  t.begin(3);
  t.openFire(fireCmd(15, 1000, 50, 0, 400));
  t.closeFire(300);
  DoseRecord r;
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.onUs[0], 300u);
  EXPECT_EQ(r.onUs[1], 50u);
  EXPECT_EQ(r.onUs[2], 0u);
  EXPECT_EQ(r.onUs[3], 300u);
}

TEST(DoseTally, AChainsLedLitAcrossAProgramEndCountsInEach) {
  DoseTally t;
  t.begin(2);
  const uint32_t p0[] = {word(1000, 1), word(500, 3)};  // LED 0 on at 1000, LED 1 too at 1500
  const uint32_t p1[] = {word(300, 2), word(200, 0)};   // LED 0 off 300 later, LED 1 200 after
  t.program(p0, 2, DoseTally::kWhole);
  t.program(p1, 2, DoseTally::kWhole);
  DoseRecord r;
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.program, 0u);
  EXPECT_EQ(r.onUs[0], 500u);
  EXPECT_EQ(r.onUs[1], 0u);
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.exposure, 2u);
  EXPECT_EQ(r.program, 1u);
  EXPECT_EQ(r.onUs[0], 300u);
  EXPECT_EQ(r.onUs[1], 500u);
}

TEST(DoseTally, ACutProgramStopsAtTheCut) {
  DoseTally t;
  t.begin(5);
  const uint32_t p[] = {word(10, 4), word(100, 0), word(10, 4), word(100, 0)};
  t.program(p, 4, 150);  // cut 30 µs into the second stretch
  DoseRecord r;
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.onUs[2], 130u);
  t.program(p, 4, 5);  // cut before its first event: nothing lit
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.program, 1u);
  EXPECT_EQ(r.onUs[2], 0u);
}

TEST(DoseTally, AFullQueueLosesTheNewRecordAndItsNumberShowsIt) {
  DoseTally t;
  t.begin(1);
  const uint32_t p[] = {word(10, 1), word(20, 0)};
  for (int k = 0; k < 3; k++) t.program(p, 2, DoseTally::kWhole);
  EXPECT_EQ(t.waiting(), DoseTally::kRecords);
  DoseRecord r;
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.program, 0u);
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.program, 1u);
  EXPECT_FALSE(t.take(r));  // program 2 found the queue full
  t.program(p, 2, DoseTally::kWhole);
  ASSERT_TRUE(t.take(r));
  EXPECT_EQ(r.program, 3u);
  EXPECT_EQ(r.onUs[0], 20u);
}
