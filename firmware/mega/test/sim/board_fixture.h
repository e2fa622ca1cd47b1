// The simavr rig's test fixture: both real images booted to `start`, and a host that sends a line
// and runs until its ok.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "board_sim.h"
#include "dialect_frame.h"

// The stack's deepest point over every board this binary ran, and the test that reached it
// (stack_sim_test.cpp reports it at the end).
struct StackMark {
  uint16_t deepest = 0xffff;
  uint16_t bytes = 0;
  uint16_t staticEnd = 0;
  std::string test;
};
inline StackMark& stackMark() {
  static StackMark mark;
  return mark;
}

class BoardTest : public ::testing::Test {
 protected:
  BoardSim sim{MEGA_ELF, NANO_ELF};
  std::vector<std::string> seen;

  // Sends a plain line and runs until its ok; returns what the Mega said meanwhile.
  std::vector<std::string> cmd(const std::string& line, double maxUs = 5e6) {
    sim.send(line + "\n");
    std::vector<std::string> got;
    bool done = sim.runUntil([&] {
      for (std::string& l : sim.takeLines()) {
        got.push_back(l);
        seen.push_back(l);
      }
      return !got.empty() && got.back().rfind("ok", 0) == 0;
    }, maxUs);
    if (!done) got.push_back("(no ok)");
    return got;
  }
  // Sends a numbered line (a job's records must be) and runs until the ok that names it.
  uint32_t lineNo = 0;
  std::vector<std::string> numbered(const std::string& body) {
    char frame[128];
    uv::encodeFrame(++lineNo, body.c_str(), frame, sizeof frame);
    std::string ok = "ok N" + std::to_string(lineNo) + " ";
    sim.send(std::string(frame) + "\n");
    std::vector<std::string> got;
    sim.runUntil([&] {
      for (std::string& l : sim.takeLines()) {
        got.push_back(l);
        seen.push_back(l);
      }
      return !got.empty() && got.back().rfind(ok, 0) == 0;
    }, 5e6);
    return got;
  }
  bool said(const std::vector<std::string>& lines, const std::string& prefix) {
    for (const std::string& l : lines)
      if (l.rfind(prefix, 0) == 0) return true;
    return false;
  }
  void TearDown() override {
    StackMark& mark = stackMark();
    if (sim.stackDeepest() < mark.deepest) {
      mark.deepest = sim.stackDeepest();
      mark.bytes = sim.stackBytes();
      mark.staticEnd = sim.staticEnd();
      mark.test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    }
  }
  void SetUp() override {
    sim.switchAt[0] = -160;  // 2 mm from where the head starts
    sim.switchAt[1] = -80;
    sim.switchAt[2] = -200;  // 0.5 mm
    ASSERT_TRUE(sim.runUntil([&] {
      for (std::string& l : sim.takeLines()) seen.push_back(l);
      return !seen.empty();
    }, 2e6));
    EXPECT_EQ(seen.front(), "start");
  }
};

