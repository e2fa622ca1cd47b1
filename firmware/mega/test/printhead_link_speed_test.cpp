// The printhead link's speed (protocol/nano.md "Link speed") against the real Nano command logic on a
// wire where each side has its own speed: raised to 250000 and proved both ways, and back to 115200
// on every doubt (a Nano reset mid-job, a missed reply, an R), then raised again when idle.
#include <gtest/gtest.h>

#include <algorithm>

#include "printhead_link_fixture.h"

using namespace mega;

namespace {

struct Speed : LinkFixture {
  void SetUp() override {
    start(true);
    ASSERT_TRUE(runUntilRaised(600000));
  }
};

const uint32_t kUs[4] = {1500, 3000, 0, 700};

}  // namespace

TEST_F(Speed, RaisedOnceIdleAndProvedByAVAtTheNewSpeed) {
  auto l = std::find(nano.lines.begin(), nano.lines.end(), "L:250000");
  ASSERT_NE(l, nano.lines.end());
  ASSERT_NE(l + 1, nano.lines.end());
  EXPECT_EQ(*(l + 1), "V");  // the first line at the new speed: the probe
  EXPECT_TRUE(bothAt(kNanoFastBaud));
  EXPECT_EQ(link.baud(), kNanoFastBaud);
  // At the new speed everything works as before: polls, and an exposure checked by S and E.
  ASSERT_TRUE(link.fire(0b1011, kUs, now));
  run(20000);
  EXPECT_EQ(link.fireState(), FireState::Done);
  ASSERT_FALSE(nano.exposures.empty());
  EXPECT_EQ(nano.exposures.back().litUs[1], 3000u);
  run(1000000);
  EXPECT_TRUE(link.raised());
  EXPECT_TRUE(link.online());
  EXPECT_EQ(link.takeEvents() & PrintheadLink::kWentOffline, 0);
}

TEST_F(Speed, ANanoResetMidJobFallsBackTo115200AndTheLinkGoesOn) {
  ASSERT_TRUE(link.fire(0b0001, kUs, now));
  run(1500);  // the F has crossed the wire (20 bytes at 250000) and is lit
  ASSERT_EQ(nano.lit(), 1);
  nano.powerCycle();  // the Nano restarts: LEDs dark, at 115200 from its first instruction
  EXPECT_EQ(nano.nanoBaud(), uv::kNanoBaud);
  uint32_t reset = now;
  while (nano.megaBaud() != uv::kNanoBaud && now - reset < 200000) run(100);
  // The Mega's next poll went unanswered (noise to a Nano at 115200): it fell back within one time-out.
  EXPECT_LE(now - reset, kNanoReplyTimeoutUs + 5000);
  EXPECT_TRUE(bothAt(uv::kNanoBaud));
  EXPECT_FALSE(link.raised());
  link.requestCounters();
  run(100000);
  ASSERT_TRUE(link.countersAnswered());  // heard again, at 115200
  EXPECT_EQ(link.boot(), nano.startCount());  // and the restart is known by C
  EXPECT_TRUE(link.online());
  // Raised again only after the retry time, when idle.
  EXPECT_TRUE(runUntilRaised(kSpeedRetryUs + 1000000));
  EXPECT_TRUE(bothAt(kNanoFastBaud));
}

TEST_F(Speed, AMissedReplyFallsBackAndTheNanoFollowsAtTheMegasFirstLine) {
  nano.silent = true;  // hears and answers nothing for a while: the Nano stays at 250000
  run(600000);  // the next poll (T or E, every 500 ms) and its 50 ms time-out
  EXPECT_EQ(nano.megaBaud(), uv::kNanoBaud);  // the Mega lowered at its first missed reply
  EXPECT_EQ(nano.nanoBaud(), kNanoFastBaud);
  nano.silent = false;
  // The Mega's next line, at 115200, is noise to the Nano at 250000: it falls back at its first byte.
  uint32_t from = now;
  while (nano.nanoBaud() != uv::kNanoBaud && now - from < 1000000) run(100);
  EXPECT_LE(now - from, 600000u);  // within one poll (T every 500 ms)
  EXPECT_TRUE(bothAt(uv::kNanoBaud));
  run(1100000);  // the next polls (T and E every 500 ms) are answered
  EXPECT_TRUE(link.online());  // talking again at 115200
  EXPECT_TRUE(link.tempsKnown());
}

TEST_F(Speed, AnRTakesBothTo115200AndTheLinkIsRaisedAgainWhenIdle) {
  ASSERT_TRUE(link.fire(0b0010, kUs, now));
  run(1500);
  ASSERT_EQ(nano.lit(), 2);
  link.allOff(33);
  run(2000);  // the R crosses the wire at 250000, and both take 115200 behind it
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_NE(std::find(nano.lines.end() - 3, nano.lines.end(), "R"), nano.lines.end());  // heard whole
  EXPECT_EQ(link.fireState(), FireState::Failed);
  EXPECT_TRUE(runUntilRaised(1000000));  // not a doubt about the speed: raised again at once
  EXPECT_TRUE(bothAt(kNanoFastBaud));
}

TEST_F(Speed, NothingElseGoesWhileTheSpeedIsSettling) {
  link.allOff();  // lowers; the link raises again at its next idle poll
  run(100);
  bool sawSwitching = false;
  for (int i = 0; i < 200 && !link.raised(); i++) {
    if (link.switching()) {
      sawSwitching = true;
      EXPECT_FALSE(link.fire(0b0001, kUs, now));
      EXPECT_FALSE(link.servo('D'));
    }
    run(100);
  }
  EXPECT_TRUE(sawSwitching);
  EXPECT_TRUE(link.raised());
}

// The speed a job is planned at (jobBaud): the raised one while the link is raised or the raise has
// not failed (a fall-back after a reset is raised again), 115200 once an L goes unanswered, and the
// raised one again as soon as a raise holds.
TEST_F(Speed, JobsArePlannedAt115200OnceAnLGoesUnansweredAndRaisedAgainOnceARaiseHolds) {
  EXPECT_EQ(link.jobBaud(), kNanoFastBaud);
  nano.noRaise = true;  // the Nano restarts as one that never answers L
  nano.powerCycle();
  run(200000);
  EXPECT_FALSE(link.raised());
  EXPECT_EQ(link.baud(), uv::kNanoBaud);
  EXPECT_EQ(link.jobBaud(), kNanoFastBaud);  // a fall-back alone: the link will be raised again
  EXPECT_FALSE(link.raiseFailed());
  for (uint32_t end = now + kSpeedRetryUs + 200000; now < end && !link.raiseFailed();) run(1000);
  ASSERT_TRUE(link.raiseFailed());  // its L went unanswered
  EXPECT_EQ(link.jobBaud(), uv::kNanoBaud);
  EXPECT_TRUE(bothAt(uv::kNanoBaud));
  EXPECT_TRUE(link.online());
  nano.noRaise = false;
  ASSERT_TRUE(runUntilRaised(kSpeedRetryUs + 600000));
  EXPECT_FALSE(link.raiseFailed());
  EXPECT_EQ(link.jobBaud(), kNanoFastBaud);
}

// A board that does not raise the link plans every job at 115200.
using SpeedOff = LinkFixture;
TEST_F(SpeedOff, JobsArePlannedAt115200WhenTheLinkIsNeverRaised) {
  start(false);
  run(1000000);
  EXPECT_FALSE(link.raised());
  EXPECT_EQ(link.jobBaud(), uv::kNanoBaud);
}
