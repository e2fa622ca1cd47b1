// The Mega's printhead link against the real Nano command logic: polls, exposures with their
// S/E checks, refusals, over-temperature, a silent or stuck Nano, and R on every way out.
#include "printhead_link.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "printhead_link_fixture.h"

using namespace mega;

namespace {

struct Link : LinkFixture {
  void SetUp() override {
    start(false);  // at 115200 throughout: the speed change has its own tests
    run(600000);
  }
};

const uint32_t kUs[4] = {1500, 3000, 0, 700};

}  // namespace

TEST_F(Link, StartsWithRThenIdentifiesAndPollsTemperaturesAndFaults) {
  ASSERT_GE(nano.lines.size(), 3u);
  EXPECT_EQ(nano.lines[0], "R");
  EXPECT_EQ(nano.lines[1], "V");
  EXPECT_STREQ(link.firmware(), NANO_FIRMWARE_VERSION);  // the simulated Nano is the real one's
  EXPECT_TRUE(link.online());
  EXPECT_TRUE(link.tempsKnown());
  EXPECT_EQ(link.deciC()[0], 250);
  int t = count("T"), e = count("E");
  run(2000000);
  EXPECT_EQ(count("T") - t, 4);  // every 500 ms
  EXPECT_EQ(count("E") - e, 4);
  EXPECT_EQ(link.takeEvents(), 0);
}

TEST_F(Link, AnExposureIsFThenSWhenItShouldBeOverThenEAndDone) {
  size_t before = nano.lines.size();
  ASSERT_TRUE(link.fire(0b1011, kUs, now));
  EXPECT_FALSE(link.fire(0b1011, kUs, now));  // one at a time
  run(7000);  // the F's 21 bytes (1.8 ms), its longest light (3 ms), then S and E
  EXPECT_EQ(link.fireState(), FireState::Done);
  ASSERT_EQ(nano.exposures.size(), 1u);
  const Exposure& x = nano.exposures[0];
  EXPECT_EQ(x.mask, 0b1011);
  EXPECT_EQ(x.litUs[0], 1500u);
  EXPECT_EQ(x.litUs[1], 3000u);
  EXPECT_EQ(x.litUs[3], 700u);
  EXPECT_EQ(nano.lines[before], "F:11,1500,3000,0,700");
  std::vector<std::string> after(nano.lines.begin() + static_cast<long>(before) + 1, nano.lines.end());
  std::vector<std::string> polls;
  for (const std::string& l : after)
    if (l == "S" || l == "E") polls.push_back(l);
  // One S early (a refusal shows at once), one when it should be over, then E: no S storm.
  EXPECT_EQ(polls, (std::vector<std::string>{"S", "S", "E"}));
  link.clearFire();
  EXPECT_EQ(link.fireState(), FireState::Idle);
}

TEST_F(Link, ARefusedExposureFailsWithE33AndSaysWhy) {
  uint32_t tooLong[4] = {10000001, 0, 0, 0};  // over the Nano's 10 s cap
  ASSERT_TRUE(link.fire(1, tooLong, now));
  run(5000);  // known within ms, not after the 10 s it asked for
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_EQ(link.fireError(), 33);
  EXPECT_EQ(link.fireFlags(), uv::fault::kCapped);
  EXPECT_TRUE(nano.exposures.empty());
}

TEST_F(Link, OverTemperatureDuringAnExposureCutsItAndFailsItWithE31) {
  uint32_t long4[4] = {400000, 400000, 400000, 400000};
  ASSERT_TRUE(link.fire(15, long4, now));
  run(100000);
  nano.setTemps(650);  // 65 °C: over the Nano's 60 °C
  run(400000);
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_EQ(link.fireError(), 31);
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_LT(nano.exposures[0].litUs[0], 400000u);
  EXPECT_TRUE(link.takeEvents() & PrintheadLink::kFault);
  run(600000);
  EXPECT_EQ(link.activeFaults() & uv::fault::kOvertemp, uv::fault::kOvertemp);
  EXPECT_FALSE(link.fire(1, kUs, now) && (run(20000), link.fireState() == FireState::Done));  // refused while hot
}

TEST_F(Link, ASilentNanoIsReportedOnceAfterThreeMissedRepliesAndWelcomedBack) {
  link.takeEvents();
  nano.silent = true;
  run(2000000);
  EXPECT_FALSE(link.online());
  EXPECT_EQ(link.takeEvents(), PrintheadLink::kWentOffline);
  run(2000000);
  EXPECT_EQ(link.takeEvents(), 0);  // once
  EXPECT_FALSE(link.fire(1, kUs, now));
  nano.silent = false;
  run(1000000);
  EXPECT_TRUE(link.online());
  EXPECT_EQ(link.takeEvents(), PrintheadLink::kCameBack);
}

// W: the Nano's clock against this one (nano_clock.h), asked in the background, never while held
// for a scan pass's G, and measured again once a silent Nano comes back.
TEST_F(Link, MeasuresTheNanosClockByWAndMeasuresItAgainAfterTheNanoWasGone) {
  nano.clockPpm = 3000;
  run(2000000);
  ASSERT_TRUE(link.nanoClock().known());
  EXPECT_NEAR(link.nanoClock().ppm(), 3000, 2);
  const int w = count("W");
  link.hold(true);
  run(20000000);
  EXPECT_EQ(count("W"), w);  // nothing while a pass waits for its G
  link.hold(false);
  run(6000000);
  EXPECT_GT(count("W"), w);  // then every 5 s
  nano.silent = true;
  run(1000000);
  EXPECT_FALSE(link.nanoClock().known());
  nano.silent = false;
  nano.clockPpm = -200;  // another Nano
  run(3000000);
  ASSERT_TRUE(link.nanoClock().known());
  EXPECT_NEAR(link.nanoClock().ppm(), -200, 2);
}

TEST_F(Link, TheNanoGoingSilentMidExposureFailsItWithE30AndSendsR) {
  uint32_t long1[4] = {300000, 0, 0, 0};
  ASSERT_TRUE(link.fire(1, long1, now));
  run(1000);
  nano.silent = true;
  run(600000);
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_EQ(link.fireError(), 30);
  EXPECT_EQ(std::count(nano.lines.end() - 8, nano.lines.end(), "R"), 1);
}

TEST_F(Link, AnLedStillOnLongAfterItsTimeIsSwitchedOffWithR) {
  nano.stuck = true;
  ASSERT_TRUE(link.fire(2, kUs, now));
  run(200000);
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_EQ(link.fireError(), 33);
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_LE(nano.exposures[0].litUs[1], 3000u + kFireGraceUs + 2000u);
}

TEST_F(Link, AllOffEndsAnExposureAtOnceEvenWhenTheUartWasFull) {
  uint32_t long1[4] = {300000, 0, 0, 0};
  ASSERT_TRUE(link.fire(1, long1, now));
  run(10000);
  nano.uartFull = true;
  link.allOff(0);
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_EQ(nano.lit(), 1);  // not yet: the byte could not go
  nano.uartFull = false;
  run(300);  // the next pass sends it: two bytes on the wire
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_EQ(nano.lines.back(), "R");
  EXPECT_LE(nano.exposures[0].litUs[0], 10200u);
}

TEST_F(Link, TheProbeIsAskedWithPAndTheServoCommandsGoOut) {
  EXPECT_TRUE(link.servo('D'));
  run(1000);
  EXPECT_EQ(nano.servoUs, 647);
  nano.probe = true;
  link.requestProbe();
  run(1000);
  EXPECT_TRUE(link.probeAnswered());
  EXPECT_TRUE(link.probeTriggered());
}
