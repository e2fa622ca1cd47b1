// The Nano's dose records (protocol/nano.md "`O` reply") against what its pins showed, on the real
// image in simavr: a chain loaded while it runs, read record by record as the Mega reads them, and
// one cut by R.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nano_codec.h"
#include "nano_sim_fixture.h"

namespace {


// A photo-like pass: every cell of each LED lit for its own share of a 4 ms window (slow enough
// for the link at 115200 to load each program while the one before runs, as the planners' link
// rule makes a pass).
Events grayPass(int windows) {
  Events ev;
  for (int j = 0; j < windows; j++) {
    uint32_t w = j * 4000;
    std::array<uint32_t, 4> off;
    for (int k = 0; k < 4; k++) off[k] = w + 400 + ((j * 37 + k * 11) % 7) * 440 + k * 3;
    ev.push_back({w, 15});
    std::array<bool, 4> done{};
    for (int n = 0; n < 4; n++) {
      int first = -1;
      for (int k = 0; k < 4; k++)
        if (!done[k] && (first < 0 || off[k] < off[first])) first = k;
      done[first] = true;
      uint8_t m = 0;
      for (int k = 0; k < 4; k++) m |= done[k] ? 0 : 1 << k;
      if (ev.back().first == off[first]) ev.back().second = m;
      else ev.push_back({off[first], m});
    }
  }
  return ev;
}

std::string load(NanoRig& rig, const std::string& program) {
  rig.takeLines();
  rig.send(program);
  std::string got;
  rig.runUntil([&] {
    for (auto& l : rig.takeLines())
      if (l[0] == 'K') got = l;
    return !got.empty();
  }, 200000);
  return got;
}

// Each LED's on-time on its pin after `from`, µs, and how many stretches it had.
std::array<double, 4> pinOnUs(NanoRig& rig, uint64_t from, std::array<int, 4>& stretches) {
  std::array<double, 4> on{};
  for (int k = 0; k < 4; k++) {
    stretches[k] = 0;
    for (auto& s : pulses(rig.edges('B', 2 + k), from)) {
      on[k] += us(s.second - s.first);
      stretches[k]++;
    }
  }
  return on;
}

// Reads every waiting record (an O until O:0).
void readRecords(NanoRig& rig, std::vector<uv::NanoReply>& out) {
  for (;;) {
    std::string l = reply(rig, "O") + "\n";
    uv::NanoReply r{};
    ASSERT_TRUE(uv::parseNanoReply(l.data(), l.size(), r)) << l;
    if (r.exposure == 0) return;
    out.push_back(r);
  }
}

}  // namespace

TEST(NanoDoseSim, AChainsRecordsMatchItsPinsProgramByProgram) {
  auto rig = bootedRig();
  Events ev = grayPass(150);  // 0.6 s, several programs of 64 events
  auto chain = programs(ev);
  ASSERT_GE(chain.size(), 5u);
  ASSERT_EQ(load(*rig, chain[0]), "K:0");
  rig->clearEdges();
  rig->send("G\n");
  std::vector<uv::NanoReply> records;
  for (size_t i = 1; i < chain.size(); i++) {  // as the Mega does: Q, then O, until a buffer is free
    ASSERT_TRUE(rig->runUntil([&] {
      readRecords(*rig, records);
      return reply(*rig, "Q")[2] != '0';
    }, 2e6)) << "program " << i;
    ASSERT_EQ(load(*rig, chain[i]), "K:0") << "program " << i << " " << reply(*rig, "Q");
  }
  rig->runUntil([&] { return reply(*rig, "Q") == "Q:2,0,2"; }, 2e6);
  readRecords(*rig, records);
  ASSERT_EQ(records.size(), chain.size()) << "one record a program";
  std::array<double, 4> fromRecords{};
  for (size_t p = 0; p < records.size(); p++) {
    EXPECT_EQ(records[p].program, p);
    EXPECT_EQ(records[p].exposure, records[0].exposure);
    for (int k = 0; k < 4; k++) fromRecords[k] += records[p].onUs[k];
  }
  std::array<int, 4> stretches;
  auto pins = pinOnUs(*rig, 0, stretches);
  for (int k = 0; k < 4; k++) {
    std::printf("[nano budget] dose record: LED %d %.0f us in the records, %.2f us on the pin, %d stretches\n", k,
                fromRecords[k], pins[k], stretches[k]);
    EXPECT_GT(pins[k], 0);
    EXPECT_LE(std::fabs(fromRecords[k] - pins[k]), stretches[k] * 1.0) << "LED " << k;
  }
}

TEST(NanoDoseSim, ACutChainsLastRecordEndsAtTheCut) {
  auto rig = bootedRig();
  Events ev = {{0, 5}, {100000, 1}, {300000, 0}};  // LEDs 0 and 2 on; 2 off at 100 ms; 0 at 300 ms
  ASSERT_EQ(load(*rig, programs(ev)[0]), "K:0");
  rig->clearEdges();
  rig->send("G\n");
  for (int t = 0; t < 8; t++) {  // 150 ms into it (LED 2 done, LED 0 lit), a Q every 20 ms as the Mega sends
    rig->send("Q\n");
    rig->runUs(t < 7 ? 20000 : uv::kProgramStartLeadUs + 10000);
  }
  rig->send("R\n");
  rig->runUs(2000);
  std::vector<uv::NanoReply> records;
  readRecords(*rig, records);
  ASSERT_EQ(records.size(), 1u);
  std::array<int, 4> stretches;
  auto pins = pinOnUs(*rig, 0, stretches);
  EXPECT_NEAR(records[0].onUs[2], 100000, 1);
  EXPECT_NEAR(records[0].onUs[0], pins[0], 2.0) << "ends where the pin went dark";
  EXPECT_GT(records[0].onUs[0], 140000u);
  EXPECT_LT(records[0].onUs[0], 300000u);
  EXPECT_EQ(records[0].onUs[1] + records[0].onUs[3], 0u);
}

TEST(NanoDoseSim, AnFsRecordIsItsDurationsAndACutOnesStopsAtTheCut) {
  auto rig = bootedRig();
  rig->clearEdges();
  rig->send("F:11,1500,700,0,2500\n");
  rig->runUs(6000);  // the line's 22 bytes, then the longest LED
  std::vector<uv::NanoReply> records;
  readRecords(*rig, records);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].program, 0u);
  EXPECT_EQ(records[0].onUs[0], 1500u);
  EXPECT_EQ(records[0].onUs[1], 700u);
  EXPECT_EQ(records[0].onUs[3], 2500u);
  std::array<int, 4> stretches;
  auto pins = pinOnUs(*rig, 0, stretches);
  EXPECT_NEAR(pins[0], 1500, 1.0);
  rig->clearEdges();
  rig->send("F:1,900000,0,0,0\n");
  rig->runUs(20000);
  rig->send("R\n");
  rig->runUs(2000);
  records.clear();
  readRecords(*rig, records);
  ASSERT_EQ(records.size(), 1u);
  pins = pinOnUs(*rig, 0, stretches);
  EXPECT_NEAR(records[0].onUs[0], pins[0], 2.0);
  EXPECT_EQ(records[0].exposure, 2u);
}
