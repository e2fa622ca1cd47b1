// Host-only: the Mega's printhead link against the fake Nano on a wire where each side keeps its own
// speed, run every 100 µs of simulated time (printhead_link_test.cpp, printhead_link_speed_test.cpp).
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "fake_nano.h"
#include "printhead_link.h"

namespace mega {

struct LinkFixture : ::testing::Test {
  FakeNano nano;
  PrintheadLink link{nano};
  uint32_t now = 0;

  // Runs the main loop every 100 µs of simulated time.
  void run(uint32_t us) {
    for (uint32_t end = now + us; now < end; now += 100) {
      nano.advance(now);
      link.poll(now);
    }
  }
  // Runs until the link is raised and proved, at most `us`; false if it never is.
  bool runUntilRaised(uint32_t us) {
    for (uint32_t end = now + us; now < end && !link.raised(); now += 100) {
      nano.advance(now);
      link.poll(now);
    }
    return link.raised();
  }
  bool bothAt(uint32_t baud) { return nano.megaBaud() == baud && nano.nanoBaud() == baud; }
  int count(const std::string& line) const {
    int n = 0;
    for (const std::string& l : nano.lines) n += l == line;
    return n;
  }
  // Each byte its ten bit-times at its sender's speed (86.8 µs at 115200): the exposure's checks
  // count the F's time on the wire. Then the link starts: R, V, and the polls.
  void start(bool raise) {
    nano.wired = true;
    link.raiseSpeed(raise);
    link.begin(now);
  }
};

}  // namespace mega
