// Host tests of the scan planner's event log (ScanPlanner::keepEvents, off the AVR): a plan whose
// events are handed out from the log is the plan walked twice, whatever the log holds.
#include <gtest/gtest.h>

#include <vector>

#include "grid_cells.h"
#include "scan.h"

using namespace uv;
using namespace uvtest;

namespace {

const MotionModel kMachine{{150000, 100000}, {3000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};

// Every pass as numbers: where it is, how it is taken, and its events or its stops.
using Plan = std::vector<std::vector<uint32_t>>;

Plan planOf(const JobHeader& h, const std::vector<std::vector<uint8_t>>& grid, uint32_t cap) {
  std::vector<uint32_t> t(cap + 1);
  std::vector<uint8_t> state(cap + 1);
  ScanPlanner::EventLog log{t.data(), state.data(), cap};
  GridCells cells(grid);
  ScanPlanner planner(h, cells, kMachine);
  if (cap) planner.keepEvents(&log);
  Plan out;
  ScanPass p;
  while (planner.nextPass(p)) {
    std::vector<uint32_t> pass{static_cast<uint32_t>(p.hy), p.descending, static_cast<uint32_t>(p.first), static_cast<uint32_t>(p.last), p.stops, p.strokeUs};
    uint32_t at;
    uint8_t m;
    Stop s;
    if (p.stops) {
      while (planner.nextStop(s)) pass.insert(pass.end(), {static_cast<uint32_t>(s.hx), static_cast<uint32_t>(s.hy), s.us[0], s.us[1], s.us[2], s.us[3]});
    } else {
      while (planner.nextEvent(at, m)) pass.insert(pass.end(), {at, m});
      EXPECT_FALSE(planner.nextEvent(at, m)) << "a pass's events end once";
    }
    out.push_back(pass);
  }
  out.push_back({static_cast<uint32_t>(planner.estimateUs()), planner.passes()});
  return out;
}

}  // namespace

TEST(ScanEventLog, HandsOutThePassesWalkedEventsWhateverItHolds) {
  uint32_t seed = 31;
  auto rnd = [&](uint32_t n) {
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return seed % n;
  };
  int events = 0;
  for (Strategy strategy : {Strategy::Scan, Strategy::Mixed})
    for (DoseMap map : {DoseMap::Linear, DoseMap::Threshold}) {
      const uint16_t cols = 120, rows = 40;
      std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
      for (auto& row : grid)  // runs of light and gray between blank stretches
        for (uint16_t c = 0; c < cols;) {
          const uint16_t run = static_cast<uint16_t>(1 + rnd(12));
          const uint8_t v = rnd(3) ? 0 : static_cast<uint8_t>(1 + rnd(255));
          for (uint16_t i = 0; i < run && c < cols; i++, c++) row[c] = v;
        }
      JobHeader h{};
      h.cols = cols;
      h.rows = rows;
      h.pitchUm[0] = h.pitchUm[1] = 50;
      h.map = map;
      h.level = 128;
      h.fullUs = 2000;
      h.strategy = strategy;
      for (int k = 0; k < 4; k++) {
        h.gainPermille[k] = 1000;
        h.offsets[k][0] = static_cast<int16_t>(k % 2);
        h.offsets[k][1] = static_cast<int16_t>(k);
      }
      const Plan walked = planOf(h, grid, 0);
      ASSERT_GT(walked.size(), 5u);
      for (const auto& pass : walked) events += static_cast<int>(pass.size());
      EXPECT_EQ(planOf(h, grid, 4096), walked) << "a log that holds every pass";
      EXPECT_EQ(planOf(h, grid, 6), walked) << "a log too small for most passes: they are walked again";
    }
  std::printf("[scan log] %d numbers of plans the same with a log and without\n", events);
}
