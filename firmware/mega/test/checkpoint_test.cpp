// The resume checkpoint on the card: the latest intact slot is read back, and one whose CRC holds
// but whose content makes no sense is not.
#include "checkpoint.h"

#include <gtest/gtest.h>

#include <string.h>

#include "storage_fake.h"

using namespace mega;

namespace {

Progress progress(const char* file, uint32_t done, uint32_t count) {
  Progress p{};
  strncpy(p.file, file, sizeof p.file - 1);
  p.done = done;
  p.count = count;
  p.boot = 7;
  p.fires = 40;
  return p;
}

}  // namespace

TEST(Checkpoint, TheLatestSlotReadsBack) {
  FakeStorage sd;
  Checkpoint c(sd);
  ASSERT_TRUE(c.begin(progress("PCB.UVJ", 0, 90)));
  ASSERT_TRUE(c.write(progress("PCB.UVJ", 41, 90)));
  c.close();
  Progress p;
  ASSERT_TRUE(Checkpoint::read(sd, p));
  EXPECT_STREQ(p.file, "PCB.UVJ");
  EXPECT_EQ(p.done, 41u);
  EXPECT_EQ(p.count, 90u);
}

TEST(Checkpoint, ASlotWithAGoodCrcButNoSenseIsNotRead) {
  // M1000 S prints the checkpoint's name to the hosts: a name of any bytes would go out as they are.
  for (const char* bad : {"BAD\x01.UVJ", "A B.UVJ", "\x7f", "/ROOT.UVJ"}) {
    FakeStorage sd;
    Checkpoint c(sd);
    ASSERT_TRUE(c.begin(progress(bad, 0, 90)));
    c.close();
    Progress p;
    EXPECT_FALSE(Checkpoint::read(sd, p)) << bad;
  }
  FakeStorage sd;
  Checkpoint c(sd);
  ASSERT_TRUE(c.begin(progress("PCB.UVJ", 91, 90)));  // more done than there are
  c.close();
  Progress p;
  EXPECT_FALSE(Checkpoint::read(sd, p));
}
