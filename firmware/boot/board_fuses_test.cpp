// The boards as Arduino ships them, decoded: boot sections, lock bits and reset time-outs against the
// datasheets' tables and boards.txt's maximum_size.
#include "board_fuses.h"

#include <gtest/gtest.h>

#include "shipped_boards.h"

namespace {

uv::ShippedBoard board(const char* name) { return uv::loadShippedBoard(BOARDS_AS_SHIPPED, name); }

TEST(BoardFuses, TheNanosHighFuseGivesA2KbBootSectionWhateverItsBootloader) {
  auto nano = board("nano");
  EXPECT_EQ(uv::bootSectionBytes(nano.chip, nano.fuses), 2048u);
  EXPECT_EQ(uv::bootSectionStart(nano.chip, nano.fuses), 0x7800u);
  EXPECT_TRUE(uv::resetsToBootloader(nano.fuses));
  // boards.txt's limit is the flash less that section, not less Optiboot's 512 B.
  EXPECT_EQ(nano.maximumSize, nano.chip.flashBytes - uv::bootSectionBytes(nano.chip, nano.fuses));
}

TEST(BoardFuses, TheMegasHighFuseGivesAn8KbBootSection) {
  auto mega = board("mega");
  EXPECT_EQ(uv::bootSectionStart(mega.chip, mega.fuses), 0x3E000u);
  EXPECT_EQ(mega.maximumSize, mega.chip.flashBytes - 8192u);
}

TEST(BoardFuses, LockBits0x0FForbidWritingTheBootSectionAndUnlockedBitsDoNot) {
  EXPECT_FALSE(uv::bootSectionWritable(board("nano").fuses));
  EXPECT_FALSE(uv::bootSectionWritable(board("mega").fuses));
  EXPECT_TRUE(uv::bootSectionWritable({0xFF, 0xDA, 0xFD, 0x3F}));  // boards.txt's unlock_bits
  EXPECT_FALSE(uv::bootSectionWritable({0xFF, 0xDA, 0xFD, 0x2F}));  // mode 2: BLB12 1, BLB11 0
}

TEST(BoardFuses, LowFuse0xFFHoldsTheChipIn14ClocksAnd65MsAfterAReset) {
  auto d = uv::resetDelay(board("mega").fuses);
  EXPECT_EQ(d.clocks, 14u);
  EXPECT_DOUBLE_EQ(d.ms, 65);
  EXPECT_DOUBLE_EQ(uv::resetDelay({0xEF, 0, 0, 0}).ms, 4.1);  // SUT 10: fast rising power
  EXPECT_DOUBLE_EQ(uv::resetDelay({0xDF, 0, 0, 0}).ms, 0);    // SUT 01: BOD enabled
  EXPECT_DOUBLE_EQ(uv::resetDelay({0xCE, 0, 0, 0}).ms, 4.1);  // CKSEL0 0, SUT 00: ceramic, fast rising
}

TEST(BoardFuses, TheAutoResetPulseLastsUnderAMillisecond) {
  auto nano = board("nano");
  EXPECT_NEAR(uv::autoResetPulseMs(nano.capacitorNf, nano.pullUpOhms), 0.693, 0.001);
}

}  // namespace
