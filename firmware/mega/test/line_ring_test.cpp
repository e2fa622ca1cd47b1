// The receive window filled from the interrupt: whole lines kept however late the main loop comes,
// overlong lines flagged, empty lines ignored, and a host that ignores the window loses only its
// own extra line.
#include "line_ring.h"

#include <gtest/gtest.h>

#include <string>

using namespace mega;

namespace {
constexpr int kWindow = kUsbWindow;
// A ring with the USB port's window, its slots beside it as main.cpp keeps them.
struct UsbRing {
  LineSlot slots[kUsbWindow];
  LineRing ring{lineWindow(slots)};
};
void feed(LineRing& r, const std::string& bytes) {
  for (char c : bytes) r.received(c);
}
}  // namespace

TEST(LineRing, HoldsAWholeWindowOfLongLinesUntilTheMainLoopComes) {
  UsbRing usb;
  LineRing& r = usb.ring;
  std::string line(96, 'x');
  for (int i = 0; i < kWindow; i++) feed(r, line + "\r\n");
  EXPECT_EQ(r.free(), 0);
  for (int i = 0; i < kWindow; i++) {
    LineSlot* s = r.arrived();
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(std::string(s->text, s->len), line);
    EXPECT_FALSE(s->overflow);
    r.accepted(false);
  }
  EXPECT_EQ(r.arrived(), nullptr);
  EXPECT_EQ(r.queued(), kWindow);
  r.front();
  r.pop();
  EXPECT_EQ(r.free(), 1);
  EXPECT_EQ(r.dropped(), 0);
}

TEST(LineRing, FlagsAnOverlongLineAndKeepsItsStart) {
  UsbRing usb;
  LineRing& r = usb.ring;
  feed(r, std::string(97, 'a') + "\n" + std::string(96, 'b') + "\rc\nok\n");
  LineSlot* s = r.arrived();
  EXPECT_TRUE(s->overflow);
  EXPECT_EQ(s->len, 96);
  r.accepted(true);
  s = r.arrived();
  EXPECT_TRUE(s->overflow);  // a '\r' that is not the last byte counts
  r.accepted(true);
  s = r.arrived();
  EXPECT_FALSE(s->overflow);
  EXPECT_STREQ(s->text, "ok");
}

TEST(LineRing, EmptyLinesTakeNoSlot) {
  UsbRing usb;
  LineRing& r = usb.ring;
  feed(r, "\n\r\n\nM105\n");
  ASSERT_NE(r.arrived(), nullptr);
  EXPECT_STREQ(r.arrived()->text, "M105");
  EXPECT_EQ(r.free(), kWindow - 1);
}

TEST(LineRing, DeadSlotsAreFreedInTheirTurn) {
  UsbRing usb;
  LineRing& r = usb.ring;
  feed(r, "G28\nN1 bad\nM105\n");
  r.accepted(false);
  r.accepted(true);  // answered at once (a checksum error)
  r.accepted(false);
  EXPECT_STREQ(r.front()->text, "G28");
  r.pop();
  EXPECT_STREQ(r.front()->text, "M105");  // the dead one is skipped
  r.pop();
  EXPECT_EQ(r.front(), nullptr);
  EXPECT_EQ(r.free(), kWindow);
}

TEST(LineRing, ALineBeyondTheWindowIsDroppedWholeAndTheNextOneArrives) {
  UsbRing usb;
  LineRing& r = usb.ring;
  for (int i = 0; i < kWindow; i++) feed(r, "M105\n");
  feed(r, "M114\n");  // a host that did not wait
  EXPECT_EQ(r.dropped(), 5u);
  for (int i = 0; i < kWindow; i++) r.accepted(false);
  r.front();
  r.pop();
  feed(r, "M115\n");
  for (int i = 0; i < kWindow - 1; i++) r.pop();
  ASSERT_NE(r.arrived(), nullptr);
  EXPECT_STREQ(r.arrived()->text, "M115");
}

TEST(LineRing, TheEspPortsWindowIsTwoLinesAndAThirdIsDroppedWhole) {
  LineSlot slots[kEspWindow];
  LineRing r(lineWindow(slots));
  EXPECT_EQ(r.window(), 2);
  feed(r, std::string(96, 'a') + "\n" + std::string(96, 'b') + "\n" + "M105\n");
  EXPECT_EQ(r.dropped(), 5u);  // the host overran its window: its own extra line, and only that, is lost
  for (char c : {'a', 'b'}) {
    LineSlot* s = r.arrived();
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(std::string(s->text, s->len), std::string(96, c));
    r.accepted(false);
  }
  EXPECT_EQ(r.arrived(), nullptr);
  r.front();
  r.pop();
  EXPECT_EQ(r.free(), 1);
}
