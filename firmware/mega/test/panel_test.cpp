// The panel: rows composed from the machine's state, redrawn a changed row at a time; the three
// buttons debounced; and what pressing each does on a whole simulated Mega.
#include <gtest/gtest.h>

#include <algorithm>

#include "buttons.h"
#include "mega_rig.h"
#include "screen.h"

using namespace mega;

namespace {

std::string row(const ScreenState& s, uint8_t r) {
  char out[kScreenCols + 1];
  composeRow(s, r, out);
  return out;
}

ScreenState running() {
  ScreenState s{};
  s.mode = ScreenState::Mode::Running;
  s.homed = true;
  s.um[0] = 10500;
  s.um[1] = -2250;
  s.um[2] = 1234;
  s.stop = 120;
  s.stops = 4000;
  s.remainingS = 345;
  s.hottest = 3;
  s.hottestDeciC = 312;
  s.hottestLimitDeciC = 550;
  s.nanoOnline = true;
  return s;
}

// A display that is busy for `busyPolls` polls after each row, as the TWI one is while it sends.
struct Recorder : TextDisplay {
  void poll(uint32_t) override {
    if (busyFor) busyFor--;
  }
  bool ready() override { return busyFor == 0; }
  bool takeLost() override {
    bool l = lost;
    lost = false;
    return l;
  }
  void row(uint8_t r, const char* text) override {
    EXPECT_TRUE(ready());
    drawn.push_back({r, text});
    busyFor = busyPolls;
  }
  std::vector<std::pair<uint8_t, std::string>> drawn;
  int busyPolls = 0, busyFor = 0;
  bool lost = false;
};

}  // namespace

TEST(Screen, RowsSayStatePositionProgressAndHeatInSixteenCharacters) {
  ScreenState s = running();
  EXPECT_EQ(row(s, 0), "UV EXPOSING     ");
  EXPECT_EQ(row(s, 1), "X  10.50Y  -2.25");
  EXPECT_EQ(row(s, 2), "Z  1.234        ");
  EXPECT_EQ(row(s, 3), "stop 120/4000   ");
  EXPECT_EQ(row(s, 4), "left 5m45s      ");
  EXPECT_EQ(row(s, 5), "T3 31.2/55.0C   ");
  EXPECT_EQ(row(s, 6), "                ");
  s.fault = 31;
  s.message = "UVP-1A2B abcdefgh-too-long";
  EXPECT_EQ(row(s, 6), "fault E31       ");
  EXPECT_EQ(row(s, 7), "UVP-1A2B abcdefg");
  s.mode = ScreenState::Mode::Halted;
  s.homed = false;
  s.nanoOnline = false;
  EXPECT_EQ(row(s, 0), "UV HALTED M999  ");
  EXPECT_EQ(row(s, 1), "not homed: G28  ");
  EXPECT_EQ(row(s, 5), "printhead silent");
  for (uint8_t r = 0; r < kScreenRows; r++) EXPECT_EQ(row(s, r).size(), kScreenCols);
  // Numbers either side of the 16-bit formatting's edges.
  s.stop = 65536;
  s.stops = 81920;
  EXPECT_EQ(row(s, 3), "stop 65536/81920");
  s.stop = 9;
  s.stops = 10;
  EXPECT_EQ(row(s, 3), "stop 9/10       ");
  s.stop = 0;
  s.stops = 4294967295u;
  EXPECT_EQ(row(s, 3), "stop 0/429496729");
}

TEST(Screen, ComposesOneRowAPassAndRedrawsOnlyWhatChanged) {
  Recorder d;
  Screen screen(d);
  ScreenState s = running();
  uint32_t ms = 0;
  for (int i = 0; i < 8; i++) EXPECT_TRUE(screen.poll(s, ms += 3));  // first the whole screen, a row each pass
  EXPECT_EQ(d.drawn.size(), kScreenRows);
  d.drawn.clear();
  for (int i = 0; i < 8; i++) EXPECT_FALSE(screen.poll(s, ms += 3));
  s.stop = 121;
  int passes = 0;
  while (d.drawn.empty() && passes < 8) screen.poll(s, ms += 3), passes++;
  ASSERT_EQ(d.drawn.size(), 1u);  // found within one sweep of the rows
  EXPECT_EQ(d.drawn[0].first, 3);
  s.stop = 122;
  for (int i = 0; i < 8; i++) EXPECT_FALSE(screen.poll(s, ms += 1));  // composing no faster than every 3 ms
}

TEST(Screen, WaitsWhileTheDisplaySendsAndRedrawsAllWhenItWasLost) {
  Recorder d;
  d.busyPolls = 5;
  Screen screen(d);
  ScreenState s = running();
  uint32_t ms = 0;
  for (int i = 0; i < 8 * 6; i++) screen.poll(s, ms += 3);
  EXPECT_EQ(d.drawn.size(), kScreenRows);  // a row every sixth pass: never handed one while busy
  d.drawn.clear();
  d.lost = true;
  for (int i = 0; i < 8 * 6; i++) screen.poll(s, ms += 3);
  EXPECT_EQ(d.drawn.size(), kScreenRows);
}

TEST(Buttons, APressCountsOnceAfterFourSteadySamplesAndBounceNever) {
  Buttons b;
  uint32_t ms = 0;
  int presses = 0;
  // Contact bounce for 15 ms, then held for 200 ms, then released with bounce.
  const uint8_t bounce[] = {1, 0, 1, 1, 0, 1, 0, 0, 1, 0};
  for (uint8_t v : bounce) presses += __builtin_popcount(b.sample(v, ms += 5));
  for (int i = 0; i < 40; i++) presses += __builtin_popcount(b.sample(1, ms += 5));
  for (uint8_t v : bounce) presses += __builtin_popcount(b.sample(v ^ 1, ms += 5));
  for (int i = 0; i < 40; i++) presses += __builtin_popcount(b.sample(0, ms += 5));
  EXPECT_EQ(presses, 1);
  EXPECT_EQ(b.sample(4, ms += 1), 0);  // samples come every 5 ms, not faster
}

TEST(Panel, HomeHomesM117ShowsAndStopHaltsAtOnce) {
  MegaRig m;
  m.begin();
  m.run(600000);
  m.io.pressed = kButtonHome;
  m.run(60000);
  m.io.pressed = 0;
  m.run(8000000);
  EXPECT_EQ(MegaRig::payload(m.cmd("M114")), (std::vector<std::string>{"X:0.000 Y:0.000 Z:0.000 E:0.000 Count X:0 Y:0 Z:0"}));
  EXPECT_EQ(m.display.rows[1], "X   0.00Y   0.00");
  m.cmd("M117 UVP-1A2B");
  m.run(300000);
  EXPECT_EQ(m.display.rows[7], "UVP-1A2B        ");
  m.io.pressed = kButtonStop;
  m.run(60000);
  m.io.pressed = 0;
  m.run(300000);
  EXPECT_EQ(m.display.rows[0], "UV HALTED M999  ");
  EXPECT_TRUE(std::find(m.nano.lines.begin(), m.nano.lines.end(), "R") != m.nano.lines.end());
  EXPECT_EQ(MegaRig::payload(m.cmd("G28")), (std::vector<std::string>{"Error:E13 machine halted: send M999"}));
}
