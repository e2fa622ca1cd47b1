// The host fake of the printhead (fake_nano.h, also the simulated printer's Nano) answers O with
// dose records that match the light it logged: an F, an F cut by R, and a scan chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "fake_nano.h"
#include "scan_program.h"

using mega::FakeNano;

namespace {

struct Link {
  FakeNano nano;
  std::string ask(const std::string& line) {
    nano.write(line.data(), static_cast<uint8_t>(line.size()));
    nano.advance(nano.nowUs + 500);
    std::string got;
    for (int16_t c; (c = nano.read()) >= 0;) got += static_cast<char>(c);
    return got;
  }
  void send(const std::string& line) { nano.write(line.data(), static_cast<uint8_t>(line.size())); }
  // Runs `us`, a Q every 10 ms as the Mega polls a running pass.
  void run(uint64_t us) {
    for (uint64_t end = nano.nowUs + us; nano.nowUs < end;) {
      ask("Q\n");
      nano.advance(std::min(end, nano.nowUs + 10000));
    }
  }
};

}  // namespace

TEST(FakeNanoDose, AnFIsReportedOnceItHasGoneDark) {
  Link l;
  EXPECT_EQ(l.ask("O\n"), "O:0\n");
  l.send("F:5,300,0,120,0\n");
  l.nano.advance(l.nano.nowUs + 1000);
  EXPECT_EQ(l.ask("O\n"), "O:1,0,300,0,120,0\n");
  EXPECT_EQ(l.ask("O\n"), "O:0\n");
}

TEST(FakeNanoDose, AnFCutByRStopsAtTheCut) {
  Link l;
  l.send("F:9,5000,0,0,800\n");
  l.nano.advance(l.nano.nowUs + 2000);
  l.send("R\n");
  l.nano.advance(l.nano.nowUs + 100);
  EXPECT_EQ(l.ask("O\n"), "O:1,0,2000,0,0,800\n");
}

TEST(FakeNanoDose, AChainsRecordsAddUpToItsLight) {
  Link l;
  using Events = std::vector<std::pair<uint32_t, uint8_t>>;
  Events ev;
  for (uint32_t j = 0; j < 100; j++) ev.insert(ev.end(), {{j * 3000, 3}, {j * 3000 + 1000 + j, 1}, {j * 3000 + 2000, 0}});
  size_t taken = 0;
  struct Ctx {
    Events* events;
    size_t* taken;
  } ctx{&ev, &taken};
  uv::ProgramLines lines(
      [](void* p, uint32_t& t, uint8_t& m) {
        auto& c = *static_cast<Ctx*>(p);
        if (*c.taken == c.events->size()) return false;
        t = (*c.events)[*c.taken].first;
        m = (*c.events)[(*c.taken)++].second;
        return true;
      },
      &ctx);
  char buf[uv::kNanoMaxLine + 2];
  auto loadOne = [&]() {
    while (uint8_t n = lines.next(buf)) {
      std::string line(buf, n);
      if (line[0] != 'K') {
        l.send(line);
        continue;
      }
      EXPECT_EQ(l.ask(line), "K:0\n");
      return true;
    }
    return false;
  };
  ASSERT_TRUE(loadOne());
  l.send("G\n");
  uint64_t records[4] = {};
  int count = 0;
  auto drain = [&]() {
    for (std::string r; (r = l.ask("O\n")) != "O:0\n";) {
      unsigned e, p, t[4];
      ASSERT_EQ(sscanf(r.c_str(), "O:%u,%u,%u,%u,%u,%u", &e, &p, &t[0], &t[1], &t[2], &t[3]), 6) << r;
      EXPECT_EQ(p, static_cast<unsigned>(count)) << "programs in order, none lost";
      count++;
      for (int k = 0; k < 4; k++) records[k] += t[k];
    }
  };
  bool more = true;
  while (more) {
    l.run(10000);
    drain();
    if (l.ask("Q\n")[2] != '0') more = loadOne();
  }
  l.run(400000);
  drain();
  EXPECT_GE(count, 4);
  for (int k = 0; k < 4; k++) EXPECT_NEAR(static_cast<double>(records[k]), static_cast<double>(l.nano.onUs(k)), 1.0) << "LED " << k;
  EXPECT_GT(records[0], 0u);
}
