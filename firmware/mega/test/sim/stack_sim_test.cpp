// The Mega image's stack in simavr: its deepest point over every run of mega_sim_tests, against the
// end of static RAM as the full build (with the card) would have it. A Klipper-class controller keeps
// its stack well clear of its statics: at least 1 KB is left between them.
#include <gtest/gtest.h>

#include <cstdio>

#include "board_fixture.h"

namespace {

constexpr int kStackRoomGoal = 1024;

class StackReport : public ::testing::Environment {
 public:
  void TearDown() override {
    const StackMark& m = stackMark();
    if (m.test.empty()) return;  // no board ran (a filtered run)
    // The full build's statics end MEGA_CARD_RAM bytes higher: the card's measured cost and the
    // estimate's margin (firmware/mega/card_ram.txt).
    const int room = m.deepest - m.staticEnd;
    const int fullRoom = room - MEGA_CARD_RAM;
    std::printf("[mega budget] stack high-water mark %u B (deepest at 0x%04x, in %s); left above static RAM: %d B in this image, "
                "about %d B in the full build (goal %d B)\n",
                m.bytes, m.deepest, m.test.c_str(), room, fullRoom, kStackRoomGoal);
    EXPECT_GE(fullRoom, kStackRoomGoal);
  }
};

const auto* const kReport = ::testing::AddGlobalTestEnvironment(new StackReport);

}  // namespace
